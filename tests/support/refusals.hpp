#pragma once
/// \file
/// The check every bad-input test makes: the reader throws InputError on one line, naming the file.

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "partreg/core/errors.hpp"

namespace partreg::testing {

/// `read` must throw InputError whose one-line message names `name` and contains `words`.
inline void expect_refused(const std::function<void()>& read, const std::string& name, const std::string& words) {
  try {
    read();
    ADD_FAILURE() << name << " was accepted";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find(name), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << words << " not in: " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
}

}  // namespace partreg::testing
