// The read of a device scene that is nothing but its loop (RK4, the only integrator), its field table, what
// follows from the fields (derive) and its rules: the shape of most devices' read_<device>. nullptr when the
// scene is refused; the problems are in the reader.
#pragma once

#include <cstddef>
#include <memory>
#include <type_traits>

#include "tools/scene/loop_config.hpp"
#include "tools/scene/schema.hpp"

namespace gyrostab::tools::schema {

template <class S, std::size_t NF, std::size_t NR>
std::unique_ptr<S> read_rk4_scene(SceneReader& r, const Field<S> (&fields)[NF],
                                  std::type_identity_t<void (*)(S&)> derive, const Rule<S> (&rules)[NR]) {
  auto s = std::make_unique<S>();
  s->loop = read_loop_config(r, "rk4", {"rk4"});
  read(r, fields, *s);
  derive(*s);
  check(r, rules, *s);
  r.finish();
  if (!r.ok()) return nullptr;
  return s;
}

}  // namespace gyrostab::tools::schema
