#pragma once
// What fsi-report and fsi-study share to write their plots and folders: gnuplot (pngcairo) run
// on a script in a folder, data files gnuplot reads, and a folder that appears at once.
#include <filesystem>
#include <functional>
#include <string>

#include "driver/report_stage.hpp"

namespace hm::driver {

/// `s` as a gnuplot single-quoted string.
std::string gnuplot_quoted(const std::string& s);

/// The curve as "t v" lines (full precision) for gnuplot; InputError when it cannot be written.
void write_curve_dat(const std::filesystem::path& file, const Curve& curve);

/// The lines that start one PNG plot: terminal, output, title, grid, axis labels. Text is taken
/// literally (noenhanced: "p_low" and "Koshizuka & Oka" are no markup).
std::string plot_header(const std::string& png, const std::string& title,
                        const std::string& x_label, const std::string& y_label);

/// Runs gnuplot on `script` in `folder` (saved as plots.gp, its output in gnuplot.log);
/// InputError naming `stage` when gnuplot is missing or fails.
void run_gnuplot(const std::filesystem::path& folder, const std::string& script,
                 const std::string& stage);

/// Calls `fill` on a fresh folder beside `folder` and renames it over `folder`, so `folder` is
/// either the previous one (when `fill` throws; the staging folder is removed) or the new one.
void write_folder_atomically(const std::filesystem::path& folder,
                             const std::function<void(const std::filesystem::path&)>& fill);

/// "tip.ux [m]" → "tip.ux_m": a file name of a probe column.
std::string file_stem_of(const std::string& column);

}  // namespace hm::driver
