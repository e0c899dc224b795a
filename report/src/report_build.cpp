#include "p3at/report/report_build.hpp"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "p3at/report/report_dat.hpp"
#include "p3at/report/report_html.hpp"
#include "p3at/report/report_plots.hpp"

namespace p3at::vipars::report {
namespace {

Result<std::vector<std::size_t>> pick_slices(const std::vector<double>& axis, const std::vector<double>& values,
                                             const std::vector<double>& v_curve, const std::vector<double>& w_curve,
                                             std::size_t count, const std::string& flag) {
  if (values.empty()) return default_slices(v_curve, w_curve, count);
  return slices_at(axis, values, flag);
}

Status write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) return make_error(Error::Code::io, path + ": cannot write");
  return {};
}

}  // namespace

Result<Comparison> build_report(const Side& v, const Side& w, const BuildOptions& o, const ProgressLine& progress) {
  const auto say = [&progress](const std::string& line) {
    if (progress) progress(line);
  };
  if (Status s = check_roles(v, w); !s) return s.error();
  if (Status s = check_same_grid(v, w); !s) return s.error();
  if (!(o.thresholds.low >= 0.0 && o.thresholds.low <= o.thresholds.high && o.thresholds.high <= 1.0)) {
    return make_error(Error::Code::invalid_argument, "--region-low/--region-high: expected 0 <= low <= high <= 1");
  }

  // Hash the inputs first: an unreadable input is bad input, before anything is written.
  std::vector<InputFile> inputs;
  for (const auto& [role, path] : o.input_files) {
    Result<InputFile> f = describe_input(role, path);
    if (!f) return f.error();
    inputs.push_back(*f);
  }

  Slices slices;
  auto rmax = pick_slices(v.rmax, o.rmax_slices, v.p_radius_curve, w.p_radius_curve, o.slice_count, "--rmax-slices");
  if (!rmax) return rmax.error();
  auto tmax = pick_slices(v.tmax, o.tmax_slices, v.p_time_curve, w.p_time_curve, o.slice_count, "--tmax-slices");
  if (!tmax) return tmax.error();
  slices.rmax = *rmax;
  slices.tmax = *tmax;

  std::error_code ec;
  std::filesystem::create_directories(o.out_dir, ec);
  if (ec) return make_error(Error::Code::io, o.out_dir + ": cannot create the folder: " + ec.message());

  const Comparison comparison = compare(v, w, o.thresholds, o.limits);
  const std::string title = o.title.empty() ? (v.mission.empty() ? std::string("mission") : v.mission) : o.title;

  if (Status s = write_files(o.out_dir, figure_data(v, w, o.thresholds, slices)); !s) return s.error();
  say("wrote the data files (fig09_time.dat .. fig14_error.dat)");

  const std::vector<FigureScript> scripts = figure_scripts({v, w, o.thresholds, comparison, slices, title});
  for (const FigureScript& f : scripts) {
    if (Status s = write_text(o.out_dir + "/" + f.stem + ".gp", f.text); !s) return s.error();
  }
  if (o.render) {
    for (const FigureScript& f : scripts) {
      Result<std::string> out = render(o.gnuplot, o.out_dir, f);
      if (!out) return out.error();
      say("rendered " + f.stem + ".png and " + f.stem + ".svg" + (out->empty() ? "" : "; gnuplot said: " + *out));
    }
  }

  std::string errors = errors_json(comparison, o.thresholds).dump(2) + "\n";
  if (Status s = write_text(o.out_dir + "/errors.json", errors); !s) return s.error();
  HtmlInputs page{v, w, o.thresholds, comparison, title, inputs, o.commands, scripts, o.render, o.notes};
  if (Status s = write_text(o.out_dir + "/index.html", report_html(page)); !s) return s.error();
  say("wrote errors.json and index.html");
  return comparison;
}

}  // namespace p3at::vipars::report
