// partreg-gui: label parts, explore shape spaces and step through registrations; `--headless --script FILE`
// replays a script through OSMesa without a display (docs/gui.md).
#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>

#include "gui_app.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/render/osmesa_context.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/gui_frame.hpp"
#include "partreg/ui/script.hpp"
#include "partreg/version.hpp"

namespace partreg::app {
namespace {

// Headless: every command runs in order; a failing one stops the replay (exit 1 or 2).
int run_headless(const GuiOptions& options, ui::AppState& state, const std::vector<ui::Command>& script) {
  render::OsMesaContext context;
  ui::GuiFrame frame(state.viewport, options.antialiasing);
  std::vector<ui::Command> ignored;  // nothing clicks headlessly
  for (const ui::Command& command : script) {
    const auto start = std::chrono::steady_clock::now();
    const ui::Outcome outcome = ui::execute(state, command);
    if (!outcome.message.empty()) std::cerr << command.line << ": " << outcome.message << '\n';
    if (!outcome.screenshot_path.empty()) {
      for (int i = 0; i < kSettleFrames; ++i) frame.draw(state, 1.0 / 60.0, ignored);
      render::write_png(outcome.screenshot_path, frame.read_pixels());
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      std::cerr << command.line << ": wrote " << outcome.screenshot_path << " (" << ms << " ms)\n";
    }
    if (state.quit_requested) break;
  }
  return 0;
}

int run(const GuiOptions& options) {
  ui::AppState state;
  state.viewport.width = options.width;
  state.viewport.height = options.height;
  std::vector<ui::Command> script;
  if (!options.input.empty()) script.push_back(ui::make_command("load", {options.input}));
  if (!options.script_path.empty()) {
    const std::vector<ui::Command> read = ui::read_script(options.script_path);
    script.insert(script.end(), read.begin(), read.end());
  }
  if (options.headless) {
    if (options.script_path.empty()) throw UsageError("--headless needs --script FILE");
    return run_headless(options, state, script);
  }
  return run_window(options, state, script);
}

}  // namespace
}  // namespace partreg::app

int main(int argc, char** argv) {
  partreg::app::GuiOptions options;
  std::string antialiasing = "msaa", size = "1280x800";
  CLI::App app{"partreg-gui: label canonical meshes, explore shape spaces, step through registrations"};
  app.set_version_flag("--version", std::string("partreg-gui ") + partreg::kVersion);
  app.add_option("INPUT", options.input, "a model (.prm), a mesh to label, or a cloud to register");
  app.add_option("--script", options.script_path, "replay these commands (docs/gui.md)");
  app.add_flag("--headless", options.headless, "no window: replay --script through OSMesa");
  app.add_option("--size", size, "frame size WIDTHxHEIGHT (pixels)")->capture_default_str();
  app.add_option("--aa", antialiasing, "msaa | edge | none")->capture_default_str();
  try {
    app.parse(argc, argv);
    if (std::sscanf(size.c_str(), "%5dx%5d", &options.width, &options.height) != 2 || options.width < 64 ||
        options.height < 64 || options.width > 16384 || options.height > 16384)
      throw partreg::UsageError("--size must be WIDTHxHEIGHT, from 64x64 to 16384x16384");
    options.antialiasing = partreg::core::parse_enum<partreg::render::Antialiasing>(antialiasing);
    return partreg::app::run(options);
  } catch (const CLI::CallForHelp& error) {
    return app.exit(error);
  } catch (const CLI::CallForVersion& error) {
    return app.exit(error);
  } catch (const CLI::ParseError& error) {
    // CLI11's own codes (105, 109, ...) are not partreg's: every usage error exits 2, as the CLI does.
    std::cerr << "partreg-gui: " << error.what() << '\n';
    return 2;
  } catch (const partreg::UsageError& error) {
    std::cerr << "partreg-gui: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {  // InputError and anything a library throws: a runtime failure
    std::cerr << "partreg-gui: " << error.what() << '\n';
    return 1;
  }
}
