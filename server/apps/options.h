// Command-line options made from a field table (fields.h): one option per
// field that names one, checked against the field's range as it is parsed,
// applied over a struct only when given.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "fields.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace ballsrv {
namespace app {

// The command-line options of a field table: one per field with an option,
// checked against the field's range as it is parsed.
template <class S>
class FieldOptions {
 public:
  // an option for each field of `table` with one (of those in `only`, when
  // given), its help saying the default of `defaults`
  void add(CLI::App &app, const std::vector<Field<S>> &table, const S &defaults,
           const std::vector<std::string> &only = {});
  bool given(const std::string &key) const;
  std::string text(const std::string &key) const;  // a given option's text ("" if not given)
  void apply(S *s) const;                          // every given option with a member into *s

 private:
  struct Entry {
    const Field<S> *field;
    CLI::Option *option = nullptr;
    double real = 0.0;
    long long integer = 0;
    bool flag = false;
    std::string text;
  };
  std::deque<Entry> entries_;  // stable addresses: CLI11 writes into them
};

}  // namespace app
}  // namespace ballsrv
