#include "driver/checkpoint_io.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace hm::driver {
namespace {

using io::Dims;
using io::MatrixRM;

using ldd::points_of;
using ldd::rows_of;

template <typename T, typename F>
std::vector<std::int64_t> integers(const std::vector<T>& v, F field) {
  std::vector<std::int64_t> out;
  out.reserve(v.size());
  for (const auto& x : v) out.push_back(static_cast<std::int64_t>(field(x)));
  return out;
}

// The StepMonitor packed as one row of doubles (the order is the checkpoint format).
constexpr int monitor_fields = 16 + static_cast<int>(ldd::PhaseSeconds::count);

std::vector<double> pack(const ldd::StepMonitor& m) {
  std::vector<double> row{static_cast<double>(m.step),
                          m.time,
                          m.dt,
                          static_cast<double>(m.limit),
                          static_cast<double>(m.ppe_iterations),
                          static_cast<double>(m.ppe_passes),
                          m.ppe_residual,
                          m.ppe_converged ? 1.0 : 0.0,
                          m.max_divergence,
                          m.volume_drift,
                          m.max_speed,
                          static_cast<double>(m.escaped),
                          static_cast<double>(m.fluid),
                          static_cast<double>(m.surface),
                          static_cast<double>(m.isolated),
                          static_cast<double>(m.wall_active)};
  const auto seconds = m.seconds.values();
  row.insert(row.end(), seconds.begin(), seconds.end());
  return row;
}

ldd::StepMonitor unpack_monitor(const double* r) {
  ldd::StepMonitor m;
  m.step = static_cast<long>(r[0]);
  m.time = r[1];
  m.dt = r[2];
  m.limit = static_cast<ldd::StepLimit>(static_cast<int>(r[3]));
  m.ppe_iterations = static_cast<int>(r[4]);
  m.ppe_passes = static_cast<int>(r[5]);
  m.ppe_residual = r[6];
  m.ppe_converged = r[7] != 0.0;
  m.max_divergence = r[8];
  m.volume_drift = r[9];
  m.max_speed = r[10];
  m.escaped = static_cast<ldd::Index>(r[11]);
  m.fluid = static_cast<ldd::Index>(r[12]);
  m.surface = static_cast<ldd::Index>(r[13]);
  m.isolated = static_cast<ldd::Index>(r[14]);
  m.wall_active = static_cast<ldd::Index>(r[15]);
  m.seconds = ldd::PhaseSeconds::from_values({r + 16, ldd::PhaseSeconds::count});
  return m;
}

constexpr int coupling_fields = 16;
/// What checkpoints wrote before the structure model's time was monitored, and before its
/// iterations and energy were.
constexpr int coupling_fields_without_structure_seconds = 15;
constexpr int coupling_fields_without_energy = 9;

void pack(const coupling::CouplingMonitor& c, double* r) {
  r[0] = c.iterations;
  r[1] = c.residual;
  r[2] = c.converged ? 1.0 : 0.0;
  r[3] = c.stretch;
  r[4] = c.added_mass_measured ? 1.0 : 0.0;
  r[5] = c.seconds;
  r[6] = c.added_mass_seconds;
  r[7] = c.deformation;
  r[8] = c.peak_pressure;
  r[9] = c.solver_iterations;
  r[10] = c.energy.kinetic;
  r[11] = c.energy.strain;
  r[12] = c.energy.external_work;
  r[13] = c.energy.damping;
  r[14] = c.energy.numerical_dissipation;
  r[15] = c.structure_seconds;
}

coupling::CouplingMonitor unpack_coupling(const double* r, int fields) {
  coupling::CouplingMonitor c;
  c.iterations = static_cast<int>(r[0]);
  c.residual = r[1];
  c.converged = r[2] != 0.0;
  c.stretch = r[3];
  c.added_mass_measured = r[4] != 0.0;
  c.seconds = r[5];
  c.added_mass_seconds = r[6];
  c.deformation = r[7];
  c.peak_pressure = r[8];
  if (fields < coupling_fields_without_structure_seconds) return c;
  c.solver_iterations = static_cast<int>(r[9]);
  c.energy = {r[10], r[11], r[12], r[13], r[14]};
  if (fields < coupling_fields) return c;
  c.structure_seconds = r[15];
  return c;
}

template <int D>
void write_points(io::ArtefactWriter& w, const ldd::FlowState<D>& s) {
  const auto& p = s.points;
  const auto n = static_cast<std::uint64_t>(p.position.size());
  w.write("/points/position", rows_of<D>(p.position));
  w.write("/points/velocity", rows_of<D>(p.velocity));
  w.write("/points/pressure", p.pressure);
  w.write("/points/kind", integers(p.kind, [](ldd::PointKind k) { return static_cast<int>(k); }));
  w.write("/points/type", integers(p.type, [](ldd::PointType t) { return static_cast<int>(t); }));
  w.write("/points/wall_normal", rows_of<D>(p.wall_normal));
  w.write("/points/wall_velocity", rows_of<D>(p.wall_velocity));
  w.write("/points/wall_acceleration", rows_of<D>(p.wall_acceleration));
  w.write("/points/host_body", integers(p.host, [](const auto& h) { return h.body; }));
  w.write("/points/host_element", integers(p.host, [](const auto& h) { return h.element; }));
  std::vector<ldd::Vec<D>> bary;
  for (const auto& h : p.host) bary.push_back(h.barycentric);
  w.write("/points/host_barycentric", rows_of<D>(bary));
  std::vector<double> gradient;
  for (const auto& g : s.velocity_gradient)
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) gradient.push_back(g(a, b));
  w.write("/points/velocity_gradient", gradient.data(), Dims{n, D * D});
  w.write("/points/wall_distance", s.wall_distance);
  w.write("/points/acceleration", s.acceleration);
  w.write("/points/id", s.id);
  w.write("/neighbours/offsets", s.neighbours.offsets);
  w.write("/neighbours/indices", integers(s.neighbours.indices, [](ldd::Index i) { return i; }));
}

template <int D>
void write_walls(io::ArtefactWriter& w, const ldd::FlowState<D>& s) {
  std::vector<std::int64_t> offsets{0};
  std::vector<ldd::Vec<D>> x, v, a;
  for (std::size_t k = 0; k < s.wall_x.size(); ++k) {
    x.insert(x.end(), s.wall_x[k].begin(), s.wall_x[k].end());
    v.insert(v.end(), s.wall_v[k].begin(), s.wall_v[k].end());
    a.insert(a.end(), s.wall_a[k].begin(), s.wall_a[k].end());
    offsets.push_back(static_cast<std::int64_t>(x.size()));
  }
  w.write("/walls/offsets", offsets);
  w.write("/walls/x", rows_of<D>(x));
  w.write("/walls/v", rows_of<D>(v));
  w.write("/walls/a", rows_of<D>(a));
}

template <int D>
void write_bodies(io::ArtefactWriter& w, std::span<const coupling::FlexibleBody<D>> bodies) {
  if (bodies.empty()) return;
  const auto nb = static_cast<Eigen::Index>(bodies.size());
  const Eigen::Index m = bodies.front().modes().modes();
  MatrixRM y(nb, m), v(nb, m), a(nb, m), F(nb, m);
  std::vector<double> added, initial;
  bool strong = true;
  for (Eigen::Index b = 0; b < nb; ++b) {
    const coupling::BodyState s = bodies[static_cast<std::size_t>(b)].state();
    if (s.y.size() != m) input_error("checkpoint: flexible bodies with different mode counts");
    y.row(b) = s.y.transpose();
    v.row(b) = s.v.transpose();
    a.row(b) = s.a.transpose();
    F.row(b) = s.F.transpose();
    strong = strong && s.added_mass.size() == m * m && s.initial_added_mass.size() == m * m;
    if (!strong) continue;
    const MatrixRM am = s.added_mass, ai = s.initial_added_mass;
    added.insert(added.end(), am.data(), am.data() + am.size());
    initial.insert(initial.end(), ai.data(), ai.data() + ai.size());
  }
  w.write("/bodies/y", y);
  w.write("/bodies/v", v);
  w.write("/bodies/a", a);
  w.write("/bodies/F", F);
  // The structure model's own state beyond the interface coordinates (one body: the scene has
  // one structure), e.g. a nonlinear body's nodal displacement.
  for (const auto& [name, values] : bodies.front().state().model)
    w.write("/bodies/model/" + name,
            std::vector<double>(values.data(), values.data() + values.size()));
  if (strong) {
    const Dims dims{static_cast<std::uint64_t>(nb), static_cast<std::uint64_t>(m),
                    static_cast<std::uint64_t>(m)};
    w.write("/bodies/added_mass", added.data(), dims);
    w.write("/bodies/added_mass_initial", initial.data(), dims);
  }
}

void write_run(io::ArtefactWriter& w, const coupling::RunResult& r) {
  const auto steps = static_cast<Eigen::Index>(r.monitors.size());
  if (steps > 0) {
    MatrixRM monitors(steps, monitor_fields);
    for (Eigen::Index k = 0; k < steps; ++k) {
      const auto row = pack(r.monitors[static_cast<std::size_t>(k)]);
      for (int c = 0; c < monitor_fields; ++c) monitors(k, c) = row[static_cast<std::size_t>(c)];
    }
    w.write("/run/monitors", monitors);
  }
  if (!r.coupling.empty()) {
    const auto bodies = static_cast<Eigen::Index>(r.coupling.front().size());
    MatrixRM coupling(static_cast<Eigen::Index>(r.coupling.size()), coupling_fields * bodies);
    for (Eigen::Index k = 0; k < coupling.rows(); ++k)
      for (Eigen::Index b = 0; b < bodies; ++b)
        pack(r.coupling[static_cast<std::size_t>(k)][static_cast<std::size_t>(b)],
             &coupling(k, coupling_fields * b));
    w.write("/run/coupling", coupling);
  }
  const auto phases = r.phase_totals.values();
  w.write("/run/phase_totals", std::vector<double>(phases.begin(), phases.end()));
  if (!r.probes.time.empty()) {
    MatrixRM values(static_cast<Eigen::Index>(r.probes.rows.size()),
                    static_cast<Eigen::Index>(r.probes.rows.front().size()));
    for (Eigen::Index k = 0; k < values.rows(); ++k)
      for (Eigen::Index c = 0; c < values.cols(); ++c)
        values(k, c) = r.probes.rows[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)];
    w.write("/run/probe_time", r.probes.time);
    if (values.cols() > 0) w.write("/run/probe_values", values);
  }
  if (!r.modal.empty() && !r.modal.front().time.empty()) {
    const auto& first = r.modal.front();
    const auto m = static_cast<std::uint64_t>(first.y.front().size());
    const auto rows = static_cast<std::uint64_t>(first.time.size());
    std::vector<double> packed;
    for (const auto& h : r.modal) {
      if (h.time.size() != rows) input_error("checkpoint: modal histories of different lengths");
      for (std::size_t k = 0; k < rows; ++k) {
        packed.push_back(h.time[k]);
        for (const Eigen::VectorXd* q : {&h.y[k], &h.v[k], &h.F[k]})
          packed.insert(packed.end(), q->data(), q->data() + q->size());
      }
    }
    w.write("/run/modal", packed.data(),
            Dims{static_cast<std::uint64_t>(r.modal.size()), rows, 1 + 3 * m});
  }
}

}  // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& folder, double time) {
  return folder / "checkpoints" / fmt::format("t_{:.6f}.h5", time);
}

template <int D>
void write_checkpoint(const std::filesystem::path& path, const std::string& parameters,
                      const std::vector<io::InputRecord>& inputs, const ldd::FlowState<D>& s,
                      std::span<const coupling::FlexibleBody<D>> bodies,
                      const coupling::RunResult& run) {
  std::filesystem::create_directories(path.parent_path());
  io::ArtefactWriter w(path, io::checkpoint_schema(), "fsi-simulate", parameters, inputs);
  write_points<D>(w, s);
  write_walls<D>(w, s);
  write_bodies<D>(w, bodies);
  write_run(w, run);
  w.set_attribute("time", s.time);
  w.set_attribute("step", static_cast<std::int64_t>(s.step));
  w.set_attribute("start_time", run.start_time);
  w.set_attribute("escaped", static_cast<std::int64_t>(s.escaped));
  w.set_attribute("initial_fluid", static_cast<std::int64_t>(s.initial_fluid));
  w.set_attribute("initial_volume", s.initial_volume);
  w.set_attribute("last_volume_drift", s.last_volume_drift);
  w.set_attribute("last_max_wall_speed", s.last_max_wall_speed);
  w.set_attribute("last_max_speed", s.last_max_speed);
  w.set_attribute("neighbour_radius", s.neighbours.radius);
  w.set_attribute("snapshots", static_cast<std::int64_t>(run.snapshots));
  w.set_attribute("wall_seconds", run.wall_seconds);
  w.set_attribute("bodies", static_cast<std::int64_t>(bodies.size()));
  w.commit();
}

namespace {

double number(const io::ArtefactReader& r, const char* name) {
  const auto v = r.number_attribute(name);
  if (!v) input_error("{}: checkpoint attribute '{}' is missing", r.path().string(), name);
  return *v;
}

template <int D>
ldd::FlowState<D> read_flow(const io::ArtefactReader& r) {
  ldd::FlowState<D> s;
  auto& p = s.points;
  p.position = points_of<D>(r.read_matrix("/points/position"));
  p.velocity = points_of<D>(r.read_matrix("/points/velocity"));
  p.pressure = r.read_values("/points/pressure");
  for (auto k : r.read_index_values("/points/kind"))
    p.kind.push_back(static_cast<ldd::PointKind>(k));
  for (auto t : r.read_index_values("/points/type"))
    p.type.push_back(static_cast<ldd::PointType>(t));
  p.wall_normal = points_of<D>(r.read_matrix("/points/wall_normal"));
  p.wall_velocity = points_of<D>(r.read_matrix("/points/wall_velocity"));
  p.wall_acceleration = points_of<D>(r.read_matrix("/points/wall_acceleration"));
  const auto body = r.read_index_values("/points/host_body");
  const auto element = r.read_index_values("/points/host_element");
  const auto bary = points_of<D>(r.read_matrix("/points/host_barycentric"));
  for (std::size_t k = 0; k < body.size(); ++k)
    p.host.push_back({static_cast<int>(body[k]), static_cast<ldd::Index>(element[k]), bary[k]});
  const std::vector<double> gradient = r.read_values("/points/velocity_gradient");
  for (std::size_t k = 0; k + D * D <= gradient.size(); k += D * D) {
    ldd::Mat<D> g;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) g(a, b) = gradient[k + static_cast<std::size_t>(D * a + b)];
    s.velocity_gradient.push_back(g);
  }
  if (r.has("/points/id"))  // checkpoints before ids: the points in id order
    for (auto id : r.read_index_values("/points/id")) s.id.push_back(id);
  s.wall_distance = r.read_values("/points/wall_distance");
  s.acceleration = r.read_values("/points/acceleration");
  s.neighbours.offsets = r.read_index_values("/neighbours/offsets");
  for (auto i : r.read_index_values("/neighbours/indices"))
    s.neighbours.indices.push_back(static_cast<ldd::Index>(i));
  s.neighbours.radius = number(r, "neighbour_radius");
  const auto offsets = r.read_index_values("/walls/offsets");
  const auto x = points_of<D>(r.read_matrix("/walls/x")),
             v = points_of<D>(r.read_matrix("/walls/v")),
             a = points_of<D>(r.read_matrix("/walls/a"));
  for (std::size_t w = 0; w + 1 < offsets.size(); ++w) {
    const auto from = x.begin() + offsets[w], to = x.begin() + offsets[w + 1];
    s.wall_x.emplace_back(from, to);
    s.wall_v.emplace_back(v.begin() + offsets[w], v.begin() + offsets[w + 1]);
    s.wall_a.emplace_back(a.begin() + offsets[w], a.begin() + offsets[w + 1]);
  }
  s.time = number(r, "time");
  s.step = static_cast<long>(number(r, "step"));
  s.escaped = static_cast<ldd::Index>(number(r, "escaped"));
  s.initial_fluid = static_cast<ldd::Index>(number(r, "initial_fluid"));
  s.initial_volume = number(r, "initial_volume");
  s.last_volume_drift = number(r, "last_volume_drift");
  s.last_max_wall_speed = number(r, "last_max_wall_speed");
  s.last_max_speed = number(r, "last_max_speed");
  return s;
}

/// The structure model's extra state (/bodies/model/*; none in checkpoints of linear modes
/// written before it was kept).
std::map<std::string, Eigen::VectorXd> read_model_state(const io::ArtefactReader& r) {
  std::map<std::string, Eigen::VectorXd> state;
  if (!r.has("/bodies/model")) return state;
  for (const std::string& name : r.children("/bodies/model")) {
    const std::vector<double> values = r.read_values("/bodies/model/" + name);
    state[name] =
        Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  }
  return state;
}

std::vector<coupling::BodyState> read_bodies(const io::ArtefactReader& r, std::size_t count) {
  std::vector<coupling::BodyState> bodies(count);
  if (count == 0) return bodies;
  const MatrixRM y = r.read_matrix("/bodies/y"), v = r.read_matrix("/bodies/v"),
                 a = r.read_matrix("/bodies/a"), F = r.read_matrix("/bodies/F");
  const Eigen::Index m = y.cols();
  const bool strong = r.has("/bodies/added_mass");
  const std::vector<double> added =
      strong ? r.read_values("/bodies/added_mass") : std::vector<double>{};
  const std::vector<double> initial =
      strong ? r.read_values("/bodies/added_mass_initial") : std::vector<double>{};
  for (std::size_t b = 0; b < count; ++b) {
    const auto row = static_cast<Eigen::Index>(b);
    bodies[b].time = number(r, "time");
    bodies[b].y = y.row(row).transpose();
    bodies[b].v = v.row(row).transpose();
    bodies[b].a = a.row(row).transpose();
    bodies[b].F = F.row(row).transpose();
    if (b == 0) bodies[b].model = read_model_state(r);
    if (!strong) continue;
    bodies[b].added_mass = Eigen::Map<const MatrixRM>(added.data() + b * m * m, m, m);
    bodies[b].initial_added_mass = Eigen::Map<const MatrixRM>(initial.data() + b * m * m, m, m);
  }
  return bodies;
}

coupling::RunResult read_run(const io::ArtefactReader& r, std::size_t bodies) {
  coupling::RunResult run;
  if (r.has("/run/monitors")) {
    const MatrixRM m = r.read_matrix("/run/monitors");
    for (Eigen::Index k = 0; k < m.rows(); ++k) run.monitors.push_back(unpack_monitor(&m(k, 0)));
  }
  if (r.has("/run/coupling")) {
    const MatrixRM c = r.read_matrix("/run/coupling");
    const auto n = static_cast<Eigen::Index>(bodies);
    int fields = 0;
    for (const int known : {coupling_fields, coupling_fields_without_structure_seconds,
                            coupling_fields_without_energy})
      if (c.cols() == known * n) fields = known;
    if (fields == 0)
      input_error(
          "{}: /run/coupling has {} columns; this version reads {}, {} or {} per body ({} "
          "bodies): the checkpoint is from another version, rerun without --restart",
          r.path().string(), c.cols(), coupling_fields, coupling_fields_without_structure_seconds,
          coupling_fields_without_energy, bodies);
    for (Eigen::Index k = 0; k < c.rows(); ++k) {
      run.coupling.emplace_back();
      for (std::size_t b = 0; b < bodies; ++b)
        run.coupling.back().push_back(
            unpack_coupling(&c(k, fields * static_cast<Eigen::Index>(b)), fields));
    }
  }
  run.phase_totals = ldd::PhaseSeconds::from_values(r.read_values("/run/phase_totals"));
  if (r.has("/run/probe_time")) {
    run.probes.time = r.read_values("/run/probe_time");
    MatrixRM values;
    if (r.has("/run/probe_values")) values = r.read_matrix("/run/probe_values");
    for (Eigen::Index row = 0; row < static_cast<Eigen::Index>(run.probes.time.size()); ++row) {
      std::vector<double> v;
      for (Eigen::Index c = 0; c < values.cols(); ++c) v.push_back(values(row, c));
      run.probes.rows.push_back(std::move(v));
    }
  }
  run.modal.resize(bodies);
  if (r.has("/run/modal")) {
    const Dims dims = r.dims("/run/modal");
    const std::vector<double> packed = r.read_values("/run/modal");
    const auto m = static_cast<Eigen::Index>((dims[2] - 1) / 3);
    for (std::size_t b = 0; b < bodies && b < dims[0]; ++b)
      for (std::size_t row = 0; row < dims[1]; ++row) {
        const double* p = packed.data() + (b * dims[1] + row) * dims[2];
        run.modal[b].record(p[0], Eigen::Map<const Eigen::VectorXd>(p + 1, m),
                            Eigen::Map<const Eigen::VectorXd>(p + 1 + m, m),
                            Eigen::Map<const Eigen::VectorXd>(p + 1 + 2 * m, m));
      }
  }
  run.start_time = number(r, "start_time");
  run.snapshots = static_cast<long>(number(r, "snapshots"));
  run.wall_seconds = number(r, "wall_seconds");
  return run;
}

}  // namespace

/// The parameters without time.end: a restart may run on to another end time.
std::string without_end_time(const std::string& parameters) {
  std::string out;
  for (std::size_t start = 0; start < parameters.size();) {
    const std::size_t end = parameters.find('\n', start);
    const std::string line = parameters.substr(start, end == std::string::npos ? end : end - start);
    if (line.rfind("time.end =", 0) != 0) out += line + "\n";
    start = end == std::string::npos ? parameters.size() : end + 1;
  }
  return out;
}

template <int D>
Checkpoint<D> read_checkpoint(const std::filesystem::path& path, const std::string& parameters,
                              std::size_t bodies) {
  const io::ArtefactReader r(path, io::checkpoint_schema());
  if (without_end_time(r.provenance().parameters) != without_end_time(parameters))
    input_error(
        "{}: this checkpoint was written for other scene parameters than the run's (see "
        "fsi-inspect {}); a restart continues the same scene (time.end may differ)",
        path.string(), path.string());
  if (r.extent("dim") != static_cast<std::uint64_t>(D))
    input_error("{}: a {}-D checkpoint for a {}-D scene", path.string(), r.extent("dim"), D);
  const auto stored = static_cast<std::size_t>(number(r, "bodies"));
  if (stored != bodies)
    input_error("{}: the checkpoint holds {} flexible bodies, the scene {}", path.string(), stored,
                bodies);
  return {read_flow<D>(r), read_bodies(r, bodies), read_run(r, bodies)};
}

template void write_checkpoint<2>(const std::filesystem::path&, const std::string&,
                                  const std::vector<io::InputRecord>&, const ldd::FlowState<2>&,
                                  std::span<const coupling::FlexibleBody<2>>,
                                  const coupling::RunResult&);
template void write_checkpoint<3>(const std::filesystem::path&, const std::string&,
                                  const std::vector<io::InputRecord>&, const ldd::FlowState<3>&,
                                  std::span<const coupling::FlexibleBody<3>>,
                                  const coupling::RunResult&);
template Checkpoint<2> read_checkpoint<2>(const std::filesystem::path&, const std::string&,
                                          std::size_t);
template Checkpoint<3> read_checkpoint<3>(const std::filesystem::path&, const std::string&,
                                          std::size_t);

}  // namespace hm::driver
