// FieldOptions' definitions (options.h), for the .cpp that instantiates it
// for its table: options.cpp for the tables the clients share, config.cpp
// for the server's own.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>

#include "common.h"
#include "options.h"

namespace ballsrv {
namespace app {

template <class S>
void FieldOptions<S>::add(CLI::App &app, const std::vector<Field<S>> &table, const S &defaults,
                          const std::vector<std::string> &only) {
  for (const auto &f : table) {
    if (!f.option || (!only.empty() && std::find(only.begin(), only.end(), f.key) == only.end())) continue;
    entries_.emplace_back();
    entries_.back().field = &f;
    Entry &e = entries_.back();
    std::string range = range_text(f);
    std::string def = f.default_text ? f.default_text : value_text(f, defaults);
    std::string help = std::string(f.doc) + (def.empty() ? "" : " (default " + def + ")");
    std::visit(
        [&](auto m) {
          using M = decltype(m);
          if constexpr (std::is_same_v<M, double S::*>) {
            Bounds b = f.bounds;
            b.hi_field = nullptr;  // a bound by another field is checked once both are known
            const Field<S> *field = &f;
            e.option = app.add_option(f.option, e.real, help)->check(CLI::Validator(
                [b, field](std::string &v) -> std::string {
                  double x = 0.0;
                  if (!CLI::detail::lexical_cast(v, x)) return "expected a number, got " + v;
                  return in_bounds(b, x) ? "" : "must be in " + range_text(*field);
                },
                range));
          } else if constexpr (std::is_same_v<M, int S::*> || std::is_same_v<M, uint32_t S::*> ||
                               std::is_same_v<M, uint64_t S::*>) {
            e.option = app.add_option(f.option, e.integer, help)->check(CLI::Range(f.bounds.ilo, f.bounds.ihi));
          } else if constexpr (std::is_same_v<M, bool S::*>) {
            e.option = app.add_option(f.option, e.flag, help)->type_name("BOOL");  // true/false, 1/0, on/off
          } else if constexpr (std::is_same_v<M, ball_level S::*>) {
            e.option = app.add_option(f.option, e.text, help)->check(CLI::Validator(
                [](std::string &v) -> std::string {
                  ball_level l;
                  return parse_level(v, &l) ? "" : "expected " + level_names() + ", got \"" + v + "\"";
                },
                "LEVEL"));
          } else {
            e.option = app.add_option(f.option, e.text, help);
          }
        },
        f.member);
  }
}

template <class S>
bool FieldOptions<S>::given(const std::string &key) const {
  for (const auto &e : entries_)
    if (key == e.field->key) return e.option->count() > 0;
  return false;
}

template <class S>
std::string FieldOptions<S>::text(const std::string &key) const {
  for (const auto &e : entries_)
    if (key == e.field->key && e.option->count() > 0) return e.text;
  return "";
}

template <class S>
void FieldOptions<S>::apply(S *s) const {
  for (const auto &e : entries_) {
    if (e.option->count() == 0) continue;
    std::visit(
        [&](auto m) {
          using M = decltype(m);
          if constexpr (std::is_same_v<M, double S::*>) {
            s->*m = e.real;
          } else if constexpr (std::is_same_v<M, int S::*> || std::is_same_v<M, uint32_t S::*> ||
                               std::is_same_v<M, uint64_t S::*>) {
            s->*m = static_cast<std::remove_reference_t<decltype(s->*m)>>(e.integer);
          } else if constexpr (std::is_same_v<M, bool S::*>) {
            s->*m = e.flag;
          } else if constexpr (std::is_same_v<M, ball_level S::*>) {
            parse_level(e.text, &(s->*m));
          } else if constexpr (std::is_same_v<M, std::string S::*>) {
            s->*m = e.text;
          }
        },
        e.field->member);
  }
}

}  // namespace app
}  // namespace ballsrv
