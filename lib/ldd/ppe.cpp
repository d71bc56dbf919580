#include "ldd/ppe.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "core/errors.hpp"

namespace hm::ldd {
namespace {

bool dirichlet_type(PointType t) {
  return t == PointType::surface || t == PointType::isolated;
}

/// Neumann row of wall node i: coefficients n·g_ij into c, returns the diagonal −Σ n·g_ij.
template <int D>
double neumann_row(const PointSet<D>& pts, const Neighbours& nb, const Operators<D>& ops, Index i,
                   double* c) {
  double diagonal = 0.0;
  std::size_t k = 0;
  for (Index j : nb.of(i)) {
    const double v =
        pts.wall_normal[i].dot(gradient_weight<D>(ops, i, j, pts.position[j] - pts.position[i]));
    c[k++] = v;
    diagonal -= v;
  }
  return diagonal;
}

/// A Neumann row without a usable diagonal (§0.2 item 5): a one-point film, a jet tip.
bool weak_neumann(double diagonal, bool isolated, double dx) {
  return isolated || std::abs(diagonal) < 0.2 / dx;
}

}  // namespace

template <int D>
PoissonSystem assemble_poisson(PointSet<D>& pts, const Neighbours& nb, const Operators<D>& ops,
                               const PoissonData& data, double dx) {
  const Index n = pts.size();
  HM_ASSERT(dx > 0.0, "assemble_poisson: dx {} must be > 0", dx);
  PoissonSystem sys;
  // Neumann rows without a usable diagonal become Dirichlet (§0.2 item 5).
  std::vector<double> coeff(nb.indices.size());
  Index weak = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : weak)
  for (Index i = 0; i < n; ++i) {
    if (pts.type[i] != PointType::wall) continue;
    const double diag = neumann_row<D>(pts, nb, ops, i, coeff.data() + nb.offsets[i]);
    if (weak_neumann(diag, ops.isolated(i), dx)) {
      pts.type[i] = PointType::surface;
      ++weak;
    }
  }
  sys.weak_neumann = weak;
  sys.unknown_of.assign(static_cast<std::size_t>(n), -1);
  sys.dirichlet.assign(static_cast<std::size_t>(n), 0.0);
  for (Index i = 0; i < n; ++i) {
    if (dirichlet_type(pts.type[i])) {
      sys.dirichlet[i] = data.dirichlet.empty() ? 0.0 : data.dirichlet[i];
    } else if (pts.type[i] != PointType::inactive) {
      sys.unknown_of[i] = static_cast<Index>(sys.point_of.size());
      sys.point_of.push_back(i);
    }
  }
  const auto m = static_cast<Index>(sys.point_of.size());
  // Row sizes: unknown neighbours + the diagonal.
  std::vector<int> outer(static_cast<std::size_t>(m) + 1, 0);
  bool any_dirichlet = false;
#pragma omp parallel for schedule(static) reduction(|| : any_dirichlet)
  for (Index r = 0; r < m; ++r) {
    int c = 1;
    for (Index j : nb.of(sys.point_of[r])) {
      if (sys.unknown_of[j] >= 0)
        ++c;
      else
        any_dirichlet = true;
    }
    outer[static_cast<std::size_t>(r) + 1] = c;
  }
  std::partial_sum(outer.begin(), outer.end(), outer.begin());
  auto& A = sys.matrix;
  A.resize(m, m);
  A.resizeNonZeros(outer.back());
  std::copy(outer.begin(), outer.end(), A.outerIndexPtr());
  sys.rhs.resize(m);
  std::vector<double> known(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) known[i] = sys.dirichlet[i];
#pragma omp parallel for schedule(dynamic, 256)
  for (Index r = 0; r < m; ++r) {
    const Index i = sys.point_of[r];
    const bool wall = pts.type[i] == PointType::wall;
    const double* c = wall ? coeff.data() + nb.offsets[i] : ops.laplacian.data() + nb.offsets[i];
    double diag = 0.0, rhs = wall ? data.neumann[i] : data.source[i];
    for (std::size_t k = 0; k < static_cast<std::size_t>(nb.count(i)); ++k) diag -= c[k];
    int* col = A.innerIndexPtr() + outer[r];
    double* val = A.valuePtr() + outer[r];
    bool diagonal_written = false;
    auto put_diagonal = [&] {
      *col++ = r;
      *val++ = 1.0;
      diagonal_written = true;
    };
    const auto nbr = nb.of(i);
    for (std::size_t k = 0; k < nbr.size(); ++k) {
      const Index j = nbr[k], u = sys.unknown_of[j];
      if (u < 0) {
        rhs -= c[k] * known[j];
        continue;
      }
      if (!diagonal_written && u > r) put_diagonal();
      *col++ = u;
      *val++ = c[k] / diag;
    }
    if (!diagonal_written) put_diagonal();
    sys.rhs[r] = rhs / diag;
  }
  if (!any_dirichlet) {
    // Closed system: pin the first interior point (its row becomes p = 0).
    for (Index r = 0; r < m && sys.pinned < 0; ++r) {
      if (pts.type[sys.point_of[r]] != PointType::interior) continue;
      sys.pinned = sys.point_of[r];
      for (int k = outer[r]; k < outer[r + 1]; ++k)
        A.valuePtr()[k] = A.innerIndexPtr()[k] == r ? 1.0 : 0.0;
      sys.rhs[r] = 0.0;
    }
  }
  return sys;
}

const char* to_string(Preconditioner preconditioner) {
  switch (preconditioner) {
    case Preconditioner::jacobi:
      return "jacobi";
    case Preconditioner::ilu:
      return "ilu";
    case Preconditioner::automatic:
      return "automatic";
    case Preconditioner::boomeramg:
      return "boomeramg";
    case Preconditioner::gamg:
      return "gamg";
  }
  return "?";
}

namespace {

linsolve::Method method_of(Preconditioner p) {
  switch (p) {
    case Preconditioner::ilu:
      return linsolve::Method::ilu;
    case Preconditioner::boomeramg:
      return linsolve::Method::boomeramg;
    case Preconditioner::gamg:
      return linsolve::Method::gamg;
    case Preconditioner::jacobi:
    case Preconditioner::automatic:
      return linsolve::Method::jacobi;
  }
  return linsolve::Method::jacobi;
}

Preconditioner preconditioner_of(linsolve::Method m) {
  switch (m) {
    case linsolve::Method::jacobi:
      return Preconditioner::jacobi;
    case linsolve::Method::ilu:
      return Preconditioner::ilu;
    case linsolve::Method::boomeramg:
      return Preconditioner::boomeramg;
    case linsolve::Method::gamg:
      return Preconditioner::gamg;
  }
  return Preconditioner::jacobi;
}

linsolve::Settings settings_of(const SolverOptions& o) {
  return {.tolerance = o.tolerance,
          .max_iterations = o.max_iterations,
          .ilu_drop = o.ilu_drop,
          .ilu_fill = o.ilu_fill,
          .amg_drop = o.amg_drop};
}

}  // namespace

bool is_available(Preconditioner p) {
  return p == Preconditioner::automatic || linsolve::is_available(method_of(p));
}

SolverOptions ppe_solver_defaults(int dimension) {
  HM_ASSERT(dimension == 2 || dimension == 3, "dimension {}", dimension);
  SolverOptions o;
  o.amg_unknowns = dimension == 2 ? 2000 : 5000;
  o.amg_setup_cost = dimension == 2 ? 32.0 : 45.0;
  return o;
}

linsolve::Strategy solver_strategy(const SolverOptions& o, Index unknowns) {
  linsolve::Strategy s;
  s.primary = method_of(o.preconditioner);
  s.reuse = o.reuse;
  if (o.preconditioner != Preconditioner::automatic) return s;
  const bool amg = o.amg_unknowns > 0 && unknowns >= o.amg_unknowns &&
                   linsolve::is_available(linsolve::Method::boomeramg);
  s.primary = amg ? linsolve::Method::boomeramg : linsolve::Method::jacobi;
  s.fallback = amg ? linsolve::Method::jacobi : linsolve::Method::ilu;
  return s;
}

PoissonSolver::PoissonSolver(const SolverOptions& options) : options_(options) {
  HM_ASSERT(is_available(options.preconditioner), "PPE preconditioner {} is not built in",
            to_string(options.preconditioner));
  HM_ASSERT(options.probe_interval >= 1 && options.max_probe_interval >= options.probe_interval,
            "PPE backend trials every {} … {} matrices", options.probe_interval,
            options.max_probe_interval);
  choice_.interval = options.probe_interval;
}

linsolve::SystemSolver& PoissonSolver::chosen_backend(const linsolve::CsrMatrix& matrix,
                                                      bool same_matrix) {
  // solver_for makes them: Jacobi/ILU below amg_unknowns, BoomerAMG/Jacobi from it on.
  auto backend = [&](bool amg) -> linsolve::SystemSolver& {
    return solver_for(amg ? options_.amg_unknowns : 0);
  };
  if (choice_.started && (same_matrix || backend(choice_.amg).holds(matrix)))
    return backend(choice_.amg);
  if (choice_.started) choose_next_backend();
  choice_.started = true;
  return backend(choice_.amg);
}

void PoissonSolver::choose_next_backend() {
  auto& c = choice_;
  const int used = c.amg ? 1 : 0, other = 1 - used;
  c.cost[used] = c.current_cost;
  c.current_cost = 0.0;
  c.idle[used] = 0;
  ++c.idle[other];
  if (c.trial) {  // the trial's verdict sets when the loser is tried again
    c.trial = false;
    c.interval = c.cost[used] <= c.cost[other]
                     ? options_.probe_interval
                     : std::min(2 * c.interval, options_.max_probe_interval);
  }
  if (c.cost[other] < 0.0 || c.idle[other] >= c.interval) {
    c.amg = other == 1;
    c.trial = true;
    return;
  }
  c.amg = c.cost[1] < c.cost[0];
}

double PoissonSolver::cost_of(const SolveReport& r) const {
  const double iterations = r.iterations + r.discarded_iterations;
  if (!choice_.amg) return iterations;
  return (r.setup ? options_.amg_setup_cost : 0.0) + options_.amg_cycle_cost * iterations;
}

linsolve::SystemSolver& PoissonSolver::solver_for(Index unknowns) {
  const auto strategy = solver_strategy(options_, unknowns);
  const bool large = options_.preconditioner == Preconditioner::automatic &&
                     strategy.primary == linsolve::Method::boomeramg;
  auto& solver = large ? large_ : small_;
  if (!solver) solver = std::make_unique<linsolve::SystemSolver>(strategy, settings_of(options_));
  return *solver;
}

linsolve::SystemCounters PoissonSolver::counters() const {
  linsolve::SystemCounters sum;
  for (const auto* s : {small_.get(), large_.get()}) {
    if (s == nullptr) continue;
    const auto& c = s->counters();
    sum.solves += c.solves;
    sum.setups += c.setups;
    sum.identical_reuses += c.identical_reuses;
    sum.stale_reuses += c.stale_reuses;
    sum.rebuilds_after_growth += c.rebuilds_after_growth;
    sum.fallbacks += c.fallbacks;
  }
  return sum;
}

bool fix_at_zero(PoissonSystem& sys, std::span<const Index> points) {
  if (sys.pinned >= 0) return false;
  auto& a = sys.matrix;
  for (const Index i : points) {
    const Index r = sys.unknown_of[static_cast<std::size_t>(i)];
    HM_ASSERT(r >= 0, "fix_at_zero: point {} is not an unknown", i);
    for (int k = a.outerIndexPtr()[r]; k < a.outerIndexPtr()[r + 1]; ++k)
      a.valuePtr()[k] = a.innerIndexPtr()[k] == r ? 1.0 : 0.0;
    sys.rhs[r] = 0.0;
  }
  return true;
}

SolveReport PoissonSolver::solve(const PoissonSystem& sys, std::vector<double>& pressure,
                                 bool keep_preconditioner) {
  const auto m = static_cast<Index>(sys.point_of.size());
  HM_ASSERT(pressure.size() == sys.unknown_of.size(), "pressure has {} values for {} points",
            pressure.size(), sys.unknown_of.size());
  SolveReport rep;
  rep.unknowns = m;
  rep.nonzeros = sys.matrix.nonZeros();
  const bool choosing = options_.preconditioner == Preconditioner::automatic &&
                        options_.amg_unknowns > 0 && m >= options_.amg_unknowns &&
                        linsolve::is_available(linsolve::Method::boomeramg);
  auto& solver = choosing ? chosen_backend(sys.matrix, keep_preconditioner) : solver_for(m);
  rep.preconditioner = preconditioner_of(solver.strategy().primary);
  Eigen::VectorXd x(m);
  for (Index r = 0; r < m; ++r) x[r] = pressure[sys.point_of[r]];
  if (m == 0) {
    rep.converged = true;
  } else {
    const auto r = solver.solve(sys.matrix, sys.rhs, x, keep_preconditioner);
    rep.converged = r.converged;
    rep.preconditioner = preconditioner_of(r.method);
    rep.iterations = r.iterations;
    rep.discarded_iterations = r.discarded_iterations;
    rep.residual = r.residual;
    rep.setup = r.setup;
    rep.setup_seconds = r.setup_seconds;
    rep.solve_seconds = r.solve_seconds;
    rep.failure = r.failure;
  }
  if (choosing) choice_.current_cost += cost_of(rep);
  // A failed solve leaves the warm start in place (never a partial or non-finite iterate).
  const bool use = rep.converged || x.allFinite();
  for (std::size_t i = 0; i < pressure.size(); ++i)
    pressure[i] =
        sys.unknown_of[i] >= 0 ? (use ? x[sys.unknown_of[i]] : pressure[i]) : sys.dirichlet[i];
  return rep;
}

template <int D>
Index demote_weak_neumann_rows(PointSet<D>& pts, const Neighbours& nb, const Operators<D>& ops,
                               double dx, Index owned, std::vector<double>* wall_rows) {
  HM_ASSERT(owned <= pts.size(), "{} owned of {} points", owned, pts.size());
  Index weak = 0;
  std::vector<double> scratch;
  if (wall_rows) wall_rows->assign(nb.indices.size(), 0.0);
  for (Index i = 0; i < owned; ++i) {
    if (pts.type[i] != PointType::wall) continue;
    double* coeff = wall_rows ? wall_rows->data() + nb.offsets[i] : nullptr;
    if (!coeff) {
      scratch.resize(static_cast<std::size_t>(nb.count(i)));
      coeff = scratch.data();
    }
    if (weak_neumann(neumann_row<D>(pts, nb, ops, i, coeff), ops.isolated(i), dx)) {
      pts.type[i] = PointType::surface;
      ++weak;
    }
  }
  return weak;
}

template <int D>
PoissonRows assemble_poisson_rows(const PointSet<D>& pts, const Neighbours& nb,
                                  const Operators<D>& ops, const PoissonData& data, Index owned,
                                  std::span<const std::int64_t> global_unknown,
                                  std::int64_t global_unknowns) {
  HM_ASSERT(global_unknown.size() == static_cast<std::size_t>(pts.size()),
            "{} global unknown numbers for {} points", global_unknown.size(), pts.size());
  HM_ASSERT(data.wall_rows.empty() || data.wall_rows.size() == nb.indices.size(),
            "{} wall-row coefficients for {} neighbour pairs", data.wall_rows.size(),
            nb.indices.size());
  PoissonRows rows;
  for (Index i = 0; i < owned; ++i)
    if (global_unknown[static_cast<std::size_t>(i)] >= 0) rows.point_of.push_back(i);
  const auto m = static_cast<Index>(rows.point_of.size());
  const auto unknown = [&](Index j) { return global_unknown[static_cast<std::size_t>(j)]; };
  // Row sizes (the diagonal and the unknown neighbours), then each row written in place.
  std::vector<int> outer(static_cast<std::size_t>(m) + 1, 0);
#pragma omp parallel for schedule(static)
  for (Index r = 0; r < m; ++r) {
    const auto nbr = nb.of(rows.point_of[r]);
    outer[r + 1] = 1 + static_cast<int>(std::count_if(nbr.begin(), nbr.end(),
                                                      [&](Index j) { return unknown(j) >= 0; }));
  }
  std::partial_sum(outer.begin(), outer.end(), outer.begin());
  auto& a = rows.matrix;
  a.resize(m, static_cast<Eigen::Index>(global_unknowns));
  a.resizeNonZeros(outer.back());
  std::copy(outer.begin(), outer.end(), a.outerIndexPtr());
  rows.rhs.resize(m);
#pragma omp parallel
  {
    std::vector<double> scratch;
    std::vector<std::pair<int, double>> unordered;
#pragma omp for schedule(dynamic, 256)
    for (Index r = 0; r < m; ++r) {
      const Index i = rows.point_of[r];
      const bool wall = pts.type[i] == PointType::wall;
      const auto nbr = nb.of(i);
      const double* coeff = ops.laplacian.data() + nb.offsets[i];
      if (wall && !data.wall_rows.empty()) {
        coeff = data.wall_rows.data() + nb.offsets[i];
      } else if (wall) {
        scratch.resize(nbr.size());
        neumann_row<D>(pts, nb, ops, i, scratch.data());
        coeff = scratch.data();
      }
      double diag = 0.0, rhs = wall ? data.neumann[i] : data.source[i];
      for (std::size_t k = 0; k < nbr.size(); ++k) diag -= coeff[k];
      // In list order with the diagonal in its place: ascending unless the row reaches ghosts
      // numbered out of order (the owned unknowns are numbered in point order).
      int* column = a.innerIndexPtr() + outer[r];
      double* value = a.valuePtr() + outer[r];
      bool diagonal_written = false;
      for (std::size_t k = 0; k < nbr.size(); ++k) {
        const Index j = nbr[k];
        if (!diagonal_written && j > i) {
          *column++ = static_cast<int>(unknown(i));
          *value++ = 1.0;
          diagonal_written = true;
        }
        if (unknown(j) >= 0) {
          *column++ = static_cast<int>(unknown(j));
          *value++ = coeff[k] / diag;
        } else if (dirichlet_type(pts.type[j]) && !data.dirichlet.empty()) {
          rhs -= coeff[k] * data.dirichlet[j];
        }
      }
      if (!diagonal_written) {
        *column++ = static_cast<int>(unknown(i));
        *value++ = 1.0;
      }
      int* first = a.innerIndexPtr() + outer[r];
      if (!std::is_sorted(first, column)) {
        double* first_value = a.valuePtr() + outer[r];
        unordered.clear();
        for (auto k = 0; first + k != column; ++k) unordered.emplace_back(first[k], first_value[k]);
        std::sort(unordered.begin(), unordered.end());
        for (std::size_t k = 0; k < unordered.size(); ++k)
          std::tie(first[k], first_value[k]) = unordered[k];
      }
      rows.rhs[r] = rhs / diag;
    }
  }
  return rows;
}

SolveReport solve_poisson(const PoissonSystem& sys, std::vector<double>& pressure,
                          const SolverOptions& opt) {
  PoissonSolver solver(opt);
  return solver.solve(sys, pressure);
}

template <int D>
PoissonData ppe_data(const PointSet<D>& pts, const Neighbours& nb, const Operators<D>& ops,
                     std::span<const Vec<D>> predicted, std::span<const Vec<D>> viscous,
                     const PpeOptions<D>& opt) {
  HM_ASSERT(opt.dt > 0.0 && opt.dx > 0.0, "ppe: dt {} and dx {} must be > 0", opt.dt, opt.dx);
  const Index n = pts.size();
  PoissonData d;
  const auto grad = slip_velocity_gradient<D>(pts, nb, ops, predicted);
  d.source.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) d.source[i] = grad[i].trace();
  d.neumann.assign(static_cast<std::size_t>(n), 0.0);
  d.dirichlet.assign(static_cast<std::size_t>(n), 0.0);
  const double rho = opt.density;
  const bool volume = opt.volume_relaxation > 0.0 && opt.reference_density > 0.0;
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    d.source[i] *= rho / opt.dt;
    if (pts.kind[i] == PointKind::wall) {
      Vec<D> a = opt.gravity - pts.wall_acceleration[i];
      if (!viscous.empty()) a += viscous[i];
      d.neumann[i] = rho * pts.wall_normal[i].dot(a);
      continue;
    }
    if (!volume) continue;
    bool full = true;  // no wall node within 2 dx, no Dirichlet neighbour
    for (Index j : nb.of(i)) {
      const bool near_wall = pts.kind[j] == PointKind::wall &&
                             (pts.position[j] - pts.position[i]).norm() < 2.0 * opt.dx;
      full = full && !near_wall && !dirichlet_type(pts.type[j]);
    }
    if (full)
      d.source[i] -= opt.volume_relaxation * rho /
                     (opt.dt * std::max(opt.dt, opt.volume_time_scale)) *
                     (ops.number_density[i] - opt.reference_density) / opt.reference_density;
  }
  return d;
}

template PoissonSystem assemble_poisson<2>(PointSet<2>&, const Neighbours&, const Operators<2>&,
                                           const PoissonData&, double);
template PoissonSystem assemble_poisson<3>(PointSet<3>&, const Neighbours&, const Operators<3>&,
                                           const PoissonData&, double);
template Index demote_weak_neumann_rows<2>(PointSet<2>&, const Neighbours&, const Operators<2>&,
                                           double, Index, std::vector<double>*);
template Index demote_weak_neumann_rows<3>(PointSet<3>&, const Neighbours&, const Operators<3>&,
                                           double, Index, std::vector<double>*);
template PoissonRows assemble_poisson_rows<2>(const PointSet<2>&, const Neighbours&,
                                              const Operators<2>&, const PoissonData&, Index,
                                              std::span<const std::int64_t>, std::int64_t);
template PoissonRows assemble_poisson_rows<3>(const PointSet<3>&, const Neighbours&,
                                              const Operators<3>&, const PoissonData&, Index,
                                              std::span<const std::int64_t>, std::int64_t);
template PoissonData ppe_data<2>(const PointSet<2>&, const Neighbours&, const Operators<2>&,
                                 std::span<const Vec<2>>, std::span<const Vec<2>>,
                                 const PpeOptions<2>&);
template PoissonData ppe_data<3>(const PointSet<3>&, const Neighbours&, const Operators<3>&,
                                 std::span<const Vec<3>>, std::span<const Vec<3>>,
                                 const PpeOptions<3>&);

}  // namespace hm::ldd
