#include "driver/gnuplot.hpp"

#include <unistd.h>
#include <cctype>
#include <cstdlib>
#include <fstream>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace hm::driver {

std::string gnuplot_quoted(const std::string& s) {
  std::string out = "'";
  for (const char ch : s) out += ch == '\'' ? std::string("''") : std::string(1, ch);
  return out + "'";
}

void write_curve_dat(const std::filesystem::path& file, const Curve& curve) {
  std::ofstream out(file);
  out.precision(17);
  for (std::size_t k = 0; k < curve.t.size(); ++k) out << curve.t[k] << ' ' << curve.v[k] << '\n';
  if (!out) input_error("{}: cannot write", file.string());
}

std::string plot_header(const std::string& png, const std::string& title,
                        const std::string& x_label, const std::string& y_label) {
  return fmt::format(
      "set terminal pngcairo noenhanced size 960,560 font ',10'\nset output {}\nset title {}\nset grid\n"
      "set key top left\nset xlabel {}\nset ylabel {}\n",
      gnuplot_quoted(png), gnuplot_quoted(title), gnuplot_quoted(x_label), gnuplot_quoted(y_label));
}

void run_gnuplot(const std::filesystem::path& folder, const std::string& script,
                 const std::string& stage) {
  const auto file = folder / "plots.gp";
  {
    std::ofstream out(file);
    out << script;
  }
  const std::string command =
      fmt::format("cd '{}' && gnuplot plots.gp > gnuplot.log 2>&1", folder.string());
  const int status = std::system(command.c_str());
  if (status != 0)
    input_error(
        "{}: gnuplot failed (exit status {}) on {}; see {} (is gnuplot installed? "
        "Debian: gnuplot-nox)",
        stage, status, file.string(), (folder / "gnuplot.log").string());
}

void write_folder_atomically(const std::filesystem::path& folder,
                             const std::function<void(const std::filesystem::path&)>& fill) {
  const std::filesystem::path staging =
      folder.parent_path() / fmt::format(".{}.tmp-{}", folder.filename().string(), ::getpid());
  std::filesystem::remove_all(staging);
  std::filesystem::create_directories(staging);
  try {
    fill(staging);
  } catch (...) {
    std::filesystem::remove_all(staging);
    throw;
  }
  std::filesystem::remove_all(folder);
  std::filesystem::rename(staging, folder);
}

std::string file_stem_of(const std::string& column) {
  std::string out;
  for (const char ch : column) {
    if (std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_')
      out += ch;
    else if (!out.empty() && out.back() != '_')
      out += '_';
  }
  while (!out.empty() && (out.back() == '_' || out.back() == '.')) out.pop_back();
  return out;
}

}  // namespace hm::driver
