// Whitespace-separated tokens with their line numbers, for the SBPL text formats (.cfg, .mprim),
// so every parse error can name the file and line.
#pragma once

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "amha_planner/lattice/map_types.h"

namespace amha {
namespace lattice {
namespace detail {

class Tokenizer {
 public:
  Tokenizer(std::istream& in, std::string name, LatticeError::Kind kind)
      : in_(in), name_(std::move(name)), kind_(kind) {}

  const std::string& name() const { return name_; }
  int line() const { return line_; }

  /// The next token, or an empty string at the end of the input.
  std::string next() {
    int c;
    while ((c = in_.get()) != EOF) {
      if (c == '\n') {
        ++line_;
      } else if (!std::isspace(c)) {
        break;
      }
    }
    token_line_ = line_;
    std::string t;
    while (c != EOF && !std::isspace(c)) {
      t.push_back(static_cast<char>(c));
      c = in_.get();
    }
    if (c == '\n') in_.unget();  // count the newline on the next call
    return t;
  }
  /// Line of the token last returned by next().
  int tokenLine() const { return token_line_; }

  [[noreturn]] void fail(const std::string& what) const { failAt(token_line_, what); }
  [[noreturn]] void failAt(int line, const std::string& what) const {
    std::ostringstream m;
    m << name_ << ":" << line << ": " << what;
    throw LatticeError(kind_, m.str());
  }

  /// Reads `label` (e.g. "resolution_m:") or fails naming what was found instead.
  void expect(const std::string& label) {
    const std::string t = next();
    if (t != label) {
      fail("expected '" + label + "' but found " +
           (t.empty() ? "the end of the file" : "'" + t + "'"));
    }
  }

  double number(const char* what) {
    const std::string t = next();
    if (t.empty()) fail(std::string("expected ") + what + " but found the end of the file");
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end != '\0' || !std::isfinite(v)) {
      fail(std::string("expected ") + what + " (a number) but found '" + t + "'");
    }
    return v;
  }

  long integer(const char* what) {
    const std::string t = next();
    if (t.empty()) fail(std::string("expected ") + what + " but found the end of the file");
    char* end = nullptr;
    const long v = std::strtol(t.c_str(), &end, 10);
    if (end == t.c_str() || *end != '\0') {
      fail(std::string("expected ") + what + " (an integer) but found '" + t + "'");
    }
    return v;
  }

 private:
  std::istream& in_;
  std::string name_;
  LatticeError::Kind kind_;
  int line_ = 1;
  int token_line_ = 1;
};

}  // namespace detail
}  // namespace lattice
}  // namespace amha
