#include "partreg/ui/script.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "partreg/core/errors.hpp"

namespace partreg::ui {
namespace {

// Arity and accepted options of each verb: min..max positional arguments.
struct Signature {
  int min_arguments = 0;
  int max_arguments = 0;
  std::vector<std::string> options;
  std::string synopsis;
};

const std::map<std::string, Signature>& signatures() {
  static const std::map<std::string, Signature> table = {
      {"load", {1, 1, {}, "PATH  (a model .prm, a mesh to label, or a cloud to register)"}},
      {"load_observed", {1, 1, {"points"}, "PATH [points=N]  (a cloud or a mesh sampled to N points)"}},
      {"load_frames",
       {1, 1, {}, "PATH  (frames on the canonical, e.g. grasps: drawn at the registration's end)"}},
      {"load_labels", {1, 1, {}, "PATH  (a labels file for the loaded mesh)"}},
      {"save_labels", {1, 1, {}, "PATH"}},
      {"mode", {1, 1, {}, "labelling | shape | registration"}},
      {"create_part", {1, 1, {}, "NAME"}},
      {"select_part", {1, 1, {}, "NAME"}},
      {"rename_part", {2, 2, {}, "NAME NEW_NAME"}},
      {"recolor_part", {4, 4, {}, "NAME R G B  (0-255)"}},
      {"merge_part", {2, 2, {}, "FROM INTO"}},
      {"delete_part", {1, 1, {}, "NAME"}},
      {"paint", {2, 2, {"radius"}, "X Y [radius=PIXELS]  (pixels from the top-left corner)"}},
      {"fill", {2, 2, {}, "X Y"}},
      {"select_box", {1, 1, {}, "X0,Y0,Z0,X1,Y1,Z1"}},
      {"select_plane", {1, 1, {}, "PX,PY,PZ,NX,NY,NZ"}},
      {"select_sphere", {1, 1, {}, "CX,CY,CZ,R"}},
      {"brush", {1, 1, {}, "RADIUS_PIXELS"}},
      {"undo", {0, 0, {}, ""}},
      {"redo", {0, 0, {}, ""}},
      {"space", {1, 1, {}, "holistic | PART"}},
      {"set_latent", {3, 3, {}, "SPACE K VALUE  (K from 1; VALUE in standard deviations)"}},
      {"animate", {1, 2, {}, "SPACE K | off  (slider K sweeps -2..+2 sd, 4 s a cycle)"}},
      {"reset_latents", {0, 1, {}, "[SPACE]"}},
      {"show_instance",
       {1,
        1,
        {},
        "NAME | INDEX | none  (a training instance drawn beside the sliders' shape; INDEX from 1)"}},
      {"instance_latent",
       {1, 1, {"space"}, "NAME | INDEX [space=SPACE]  (the sliders set to that training instance's latent)"}},
      {"sample_latents", {1, 1, {}, "SEED  (every slider of the current space drawn from N(0, 1))"}},
      {"register",
       {1,
        1,
        {"direction", "loss", "iterations", "viewpoint"},
        "holistic | partwise | hol+part [direction=observed|canonical|symmetric] [loss=huber|squared|cauchy|"
        "trimmed] [iterations=N] [viewpoint=X,Y,Z|none]"}},
      {"save_result",
       {1, 1, {}, "FOLDER  (result.json, points.ply, mesh.ply, frames.json, as `partreg register` writes)"}},
      {"partial_view",
       {1, 1, {"count"}, "I [count=42]  (what a depth camera sees of the observation from view I)"}},
      {"perturb",
       {2, 2, {"seed"}, "noise|outliers|rotation|translation LEVEL [seed=S]  (the paper's units)"}},
      {"train", {1, 1, {"out"}, "DATASET [out=MODEL.prm]  (the labelled mesh becomes the canonical)"}},
      {"step", {1, 1, {}, "N  (forward N history steps; negative goes back)"}},
      {"goto_step", {1, 1, {}, "I | first | last"}},
      {"camera", {1, 1, {}, "front | side | top | iso"}},
      {"orbit", {2, 2, {}, "D_AZIMUTH_DEG D_ELEVATION_DEG"}},
      {"zoom", {1, 1, {}, "FACTOR  (>1 moves closer)"}},
      {"pan", {2, 2, {}, "DX DY  (pixels)"}},
      {"centre", {2, 2, {}, "X Y  (orbit about the surface point under the pixel)"}},
      {"resize", {2, 2, {}, "WIDTH HEIGHT"}},
      {"panels", {1, 1, {}, "on | off"}},
      {"screenshot", {1, 1, {}, "PATH.png"}},
      {"quit", {0, 0, {}, ""}},
  };
  return table;
}

[[noreturn]] void fail(int line_number, const std::string& what) {
  throw UsageError((line_number > 0 ? "line " + std::to_string(line_number) + ": " : std::string()) + what);
}

std::vector<std::string> tokenize(const std::string& line, int line_number) {
  std::vector<std::string> tokens;
  std::string current;
  bool in_token = false, quoted = false;
  for (const char c : line) {
    if (quoted) {
      if (c == '"')
        quoted = false;
      else
        current += c;
    } else if (c == '"') {
      quoted = in_token = true;
    } else if (c == '#') {
      break;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      if (in_token) tokens.push_back(current);
      current.clear();
      in_token = false;
    } else {
      current += c;
      in_token = true;
    }
  }
  if (quoted) fail(line_number, "unterminated quote");
  if (in_token) tokens.push_back(current);
  return tokens;
}

}  // namespace

std::string Command::option(const std::string& key, const std::string& fallback) const {
  for (const auto& [name, value] : options)
    if (name == key) return value;
  return fallback;
}

std::string Command::to_string() const {
  auto quote = [](const std::string& text) {
    return text.find(' ') == std::string::npos && !text.empty() ? text : '"' + text + '"';
  };
  std::string line = verb;
  for (const std::string& argument : arguments) line += ' ' + quote(argument);
  for (const auto& [key, value] : options) line += ' ' + key + '=' + quote(value);
  return line;
}

Command make_command(const std::string& verb, std::vector<std::string> arguments,
                     std::vector<std::pair<std::string, std::string>> options) {
  Command command;
  command.verb = verb;
  command.arguments = std::move(arguments);
  command.options = std::move(options);
  return command;
}

const std::vector<std::pair<std::string, std::string>>& command_synopses() {
  static const std::vector<std::pair<std::string, std::string>> list = [] {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& [verb, signature] : signatures()) out.emplace_back(verb, signature.synopsis);
    return out;
  }();
  return list;
}

bool parse_command(const std::string& line, int line_number, Command& command) {
  const std::vector<std::string> tokens = tokenize(line, line_number);
  if (tokens.empty()) return false;
  const auto found = signatures().find(tokens[0]);
  if (found == signatures().end()) fail(line_number, "unknown command '" + tokens[0] + "' (see docs/gui.md)");
  const Signature& signature = found->second;
  Command parsed;
  parsed.verb = tokens[0];
  parsed.line = line_number;
  for (std::size_t i = 1; i < tokens.size(); ++i) {
    const std::size_t equals = tokens[i].find('=');
    if (equals == std::string::npos || equals == 0) {
      parsed.arguments.push_back(tokens[i]);
      continue;
    }
    const std::string key = tokens[i].substr(0, equals);
    if (std::find(signature.options.begin(), signature.options.end(), key) == signature.options.end())
      fail(line_number, parsed.verb + " takes no option '" + key + "'");
    parsed.options.emplace_back(key, tokens[i].substr(equals + 1));
  }
  const int count = static_cast<int>(parsed.arguments.size());
  if (count < signature.min_arguments || count > signature.max_arguments)
    fail(line_number, "usage: " + parsed.verb + " " + signature.synopsis);
  command = std::move(parsed);
  return true;
}

std::vector<Command> parse_script(const std::string& text) {
  std::vector<Command> commands;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    Command command;
    if (parse_command(line, number, command)) commands.push_back(std::move(command));
  }
  return commands;
}

std::vector<Command> read_script(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw InputError("cannot read the script " + path.string());
  std::ostringstream text;
  text << file.rdbuf();
  try {
    return parse_script(text.str());
  } catch (const UsageError& error) {
    throw UsageError(path.string() + ": " + error.what());
  }
}

}  // namespace partreg::ui
