// `partreg figure compare MODEL OBSERVED` and `partreg figure space MODEL`: the paper's kinds of figure,
// rendered headlessly (layouts in docs/rendering.md).
#include <chrono>
#include <iostream>
#include <memory>
#include <sstream>

#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/commands/render_common.hpp"
#include "partreg/commands/setting_flags.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/progress.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/render/figure.hpp"

namespace partreg::app {
namespace {

struct FigureOptions {
  std::string model_path, observed_path, variants = "holistic,hol+part", space = "holistic", out;
  std::string size, view = "iso", background = "white";
  std::size_t observed_samples = 3000;
  std::string antialias = "msaa";
  core::RegistrationSettings registration;  ///< every variant's settings but the variant itself
  int threads = 0;
};

render::FigureSettings figure_settings(const FigureOptions& options, const std::string& default_size) {
  render::FigureSettings settings;
  std::tie(settings.panel_width, settings.panel_height) =
      parse_size(options.size.empty() ? default_size : options.size, "--size");
  settings.view = core::parse_enum<render::View>(options.view);
  settings.background = core::parse_enum<render::Background>(options.background);
  settings.antialiasing = core::parse_enum<render::Antialiasing>(options.antialias);
  return settings;
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');)
    if (!part.empty()) parts.push_back(part);
  return parts;
}

void write_figure(const render::Image& image, const std::string& out,
                  std::chrono::steady_clock::time_point start) {
  render::write_png(out, image);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "wrote " << out << " (" << image.width << "x" << image.height << ", " << seconds << " s)\n";
}

void run_compare(const FigureOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const render::FigureSettings settings = figure_settings(options, "640x360");
  std::vector<core::RegistrationSettings> runs;
  for (const std::string& variant : split_commas(options.variants)) {
    core::RegistrationSettings run = options.registration;
    try {
      run.variant = core::parse_enum<core::Variant>(variant);
    } catch (const UsageError& error) {
      throw UsageError(std::string("--variants: ") + error.what());
    }
    runs.push_back(run);
  }
  if (runs.empty()) throw UsageError("--variants names no variant");
  check_output_folder(options.out);
  const core::ThreadBudget budget(options.threads);
  const core::CategoryModel model = io::read_model(options.model_path);
  const core::Points observed = read_points_logged(options.observed_path, options.observed_samples, 1);
  render::Grid grid;
  grid.columns = static_cast<int>(runs.size());
  // One bar over the registrations (a line each) and then the panels (two per variant, counts only).
  ProgressDisplay display({"steps", /*lines_are_detail=*/false, /*log_every_percent=*/25});
  const std::size_t steps = 3 * runs.size();
  const core::ProgressListener listener = display.listener();
  core::ProgressCounter registered(steps, listener);
  std::vector<render::Panel> overlays;  // the second row: each variant's fit over the observation
  for (const core::RegistrationSettings& run : runs) {
    const core::RegistrationResult result = core::register_observation(model, observed, run);
    const std::string variant = core::enum_name(result.variant);
    std::ostringstream title, line;
    title.precision(2);
    title << std::fixed << variant << ": mean fit " << 100.0 * result.fit.mean_normalised << "% of diagonal";
    line << title.str() << " (" << result.seconds << " s)";
    registered.step(line.str());
    if (verbosity() == Verbosity::verbose)
      for (const core::SpaceFit& fit : result.fits)
        display.print("  space " + fit.space + ": " + std::to_string(fit.iterations) + " steps (" +
                      core::enum_name(fit.stop_reason) + "), " + std::to_string(fit.seconds) + " s");
    grid.panels.push_back(render::comparison_panel(model, observed, result, title.str(), settings.view));
    overlays.push_back(render::overlay_panel(model, observed, result, variant + ": overlay"));
  }
  for (render::Panel& overlay : overlays) grid.panels.push_back(std::move(overlay));
  const render::Image image = render::render_grid(grid, settings, [&](const core::Progress& panel) {
    display(core::Progress{runs.size() + panel.done, steps, ""});  // the panel's title says nothing new
  });
  display.finish();
  write_figure(image, options.out, start);
}

void run_space(const FigureOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const render::FigureSettings settings = figure_settings(options, "320x240");
  check_output_folder(options.out);
  const core::CategoryModel model = io::read_model(options.model_path);
  const render::Grid grid = render::shape_space_grid(model, options.space);
  std::cerr << "space " << options.space << ": " << grid.row_labels.size() << " principal directions\n";
  ProgressDisplay display({"panels", /*lines_are_detail=*/true, /*log_every_percent=*/20});
  const render::Image image = render::render_grid(grid, settings, display.listener());
  display.finish();
  write_figure(image, options.out, start);
}

void add_shared_options(CLI::App* command, FigureOptions& o, const char* default_size) {
  command->add_option("--out", o.out, "the PNG to write")->required();
  command->add_option("--size", o.size,
                      std::string("size of each panel, WIDTHxHEIGHT (default ") + default_size + ")");
  command->add_option("--view", o.view, "iso | front | side | top (+Y up)")->capture_default_str();
  command->add_option("--background", o.background, "white | transparent")->capture_default_str();
  command->add_option("--antialias", o.antialias, "msaa (4 samples) | edge (fast) | none")
      ->capture_default_str();
}

}  // namespace

void add_figure_command(CLI::App& app) {
  auto o = std::make_shared<FigureOptions>();
  CLI::App* figure =
      app.add_subcommand("figure", "Figures of registrations and shape spaces (PNG, headless)");
  figure->require_subcommand(1);

  CLI::App* compare = figure->add_subcommand(
      "compare",
      "Observed cloud (red) and each variant's deformed canonical (parts coloured), one column each: "
      "side by side above, overlaid below");
  compare->add_option("MODEL", o->model_path, "model file from partreg train")->required();
  compare->add_option("OBSERVED", o->observed_path, "observed cloud or mesh")->required();
  compare
      ->add_option("--variants", o->variants, "comma-separated: " + core::enum_choices<core::Variant>(", "))
      ->capture_default_str();
  compare->add_option("--points", o->observed_samples, "points sampled from an observed mesh")
      ->capture_default_str()
      ->check(point_count_range());
  add_registration_flags(compare, o->registration, {"variant"});
  add_threads_flag(compare, o->threads);
  add_shared_options(compare, *o, "640x360");
  compare->callback([o] { run_compare(*o); });

  CLI::App* space = figure->add_subcommand(
      "space", "A shape space's principal directions: one row each, shapes at -2..+2 standard deviations");
  space->add_option("MODEL", o->model_path, "model file from partreg train")->required();
  space->add_option("--space", o->space, "holistic or a part's name")->capture_default_str();
  add_shared_options(space, *o, "320x240");
  space->callback([o] { run_space(*o); });
}

}  // namespace partreg::app
