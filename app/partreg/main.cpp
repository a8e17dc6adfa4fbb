// partreg: the command-line entry point. Each subcommand lives in commands/; this file only turns
// failures into one line on stderr and an exit code (0 success, 1 runtime failure, 2 usage error, 3 a
// result rejected by its own verdict: register --fail-on).
#include <iostream>
#include <string>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/version.hpp"

namespace {

// Control characters (a newline or an escape sequence in a file name) as \xNN: the error stays one line and
// cannot drive the terminal.
std::string printable(const std::string& text) {
  std::string out;
  for (const unsigned char c : text) {
    if (c >= 0x20 && c != 0x7f) {
      out += static_cast<char>(c);
      continue;
    }
    const char* digits = "0123456789abcdef";
    out += "\\x";
    out += digits[c >> 4];
    out += digits[c & 15];
  }
  return out;
}

int fail(const char* what, int code) {
  partreg::app::restore_error_stream();  // --quiet still shows the error
  std::cerr << "partreg: " << printable(what) << '\n';
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"partreg: category-level, part-based, non-rigid 3D registration"};
  app.set_version_flag("--version", std::string("partreg ") + PARTREG_VERSION);
  app.require_subcommand(1);
  partreg::app::add_cpd_command(app);
  partreg::app::add_train_command(app);
  partreg::app::add_info_command(app);
  partreg::app::add_synth_command(app);
  partreg::app::add_label_command(app);
  partreg::app::add_register_command(app);
#ifdef PARTREG_WITH_RENDER  // built with ui/ (PARTREG_BUILD_UI=ON)
  partreg::app::add_render_commands(app);
#endif
  partreg::app::add_views_command(app);
  partreg::app::add_eval_command(app);
  partreg::app::add_grasps_command(app);
  partreg::app::add_segment_command(app);
  partreg::app::add_scene_command(app);
  partreg::app::add_verbosity_flags(app);  // after every subcommand: it adds the flags to each

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(e.what(), 2);
  } catch (const partreg::UsageError& e) {
    return fail(e.what(), 2);
  } catch (const partreg::app::RejectedResult& e) {
    return fail(e.what(), 3);
  } catch (const partreg::InputError& e) {
    return fail(e.what(), 1);
  } catch (const std::exception& e) {
    return fail(e.what(), 1);
  }
  return 0;
}
