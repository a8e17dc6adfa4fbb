#include "partreg/ui/executor.hpp"

#include <utility>

#include "partreg/core/errors.hpp"
#include "verb_support.hpp"

namespace partreg::ui {
namespace {

// Every group's verbs, one table: each group declares its own (verb_support.hpp lists them).
std::vector<Verb> make_verbs() {
  std::vector<Verb> table;
  for (std::vector<Verb> (*group)() : {detail::file_verbs, detail::labelling_verbs, detail::shape_verbs,
                                       detail::registration_verbs, detail::view_verbs}) {
    std::vector<Verb> verbs = group();
    table.insert(table.end(), std::make_move_iterator(verbs.begin()), std::make_move_iterator(verbs.end()));
  }
  return table;
}

}  // namespace

const std::vector<Verb>& verbs() {
  static const std::vector<Verb> table = make_verbs();
  return table;
}

const Verb* find_verb(const std::string& name) {
  for (const Verb& verb : verbs())
    if (verb.name == name) return &verb;
  return nullptr;
}

Outcome execute(AppState& state, const Command& command) {
  const Verb* verb = find_verb(command.verb);
  if (!verb) throw UsageError("unknown command '" + command.verb + "'");
  Outcome outcome = verb->run(state, command);
  if (!outcome.message.empty() || state.status_is_error) state.status = outcome.message;
  state.status_is_error = false;
  return outcome;
}

bool execute_reporting(AppState& state, const Command& command, Outcome* outcome) {
  try {
    Outcome result = execute(state, command);
    if (outcome) *outcome = std::move(result);
    return true;
  } catch (const InputError& error) {
    state.status = error.what();
  } catch (const UsageError& error) {
    state.status = error.what();
  }
  state.status_is_error = true;
  return false;
}

}  // namespace partreg::ui
