#pragma once
// Compile-time plugin sets. Boost.Hana is confined to this header.
//
//   using MyPlugins = ftsense::reference_plugins::with<MyVirtualSensor, MyDetector>;
//   auto registry = MyPlugins::registry();      // what Pipeline::build looks plugins up in
//
// Every member is checked against the plugin contract (plugin.hpp) with one readable
// static_assert per broken rule, and names must be unique within a set.

#include <array>
#include <cstddef>
#include <string_view>

#include <boost/hana/basic_tuple.hpp>
#include <boost/hana/concat.hpp>
#include <boost/hana/for_each.hpp>
#include <boost/hana/tuple.hpp>
#include <boost/hana/type.hpp>
#include <boost/hana/unpack.hpp>

#include "ftsense/plugin_registry.hpp"

namespace ftsense {

namespace detail {
template <std::size_t N>
constexpr bool names_unique(const std::array<std::string_view, N>& names) {
  for (std::size_t i = 0; i < N; ++i) {
    for (std::size_t j = i + 1; j < N; ++j) {
      if (names[i] == names[j]) return false;
    }
  }
  return true;
}
}  // namespace detail

template <class... Ps>
struct PluginSet {
  static_assert((check_plugin<Ps>() && ...));
  static_assert(detail::names_unique(std::array<std::string_view, sizeof...(Ps)>{Ps::name...}),
                "ftsense plugin set: two plugins have the same name");

  static constexpr auto types = boost::hana::tuple_t<Ps...>;
  static constexpr std::size_t size = sizeof...(Ps);

  // This set followed by more plugin types.
  template <class... More>
  using with = PluginSet<Ps..., More...>;

  // The run-time registry of this set, in declaration order.
  static PluginRegistry registry() {
    PluginRegistry out;
    boost::hana::for_each(types, [&](auto type) {
      using P = typename decltype(type)::type;
      out.add(make_plugin_info<P>());
    });
    return out;
  }
};

namespace detail {
template <class A, class B>
struct merge_sets {
  static constexpr auto merged = boost::hana::concat(A::types, B::types);
  using type = typename decltype(boost::hana::unpack(merged, boost::hana::template_<PluginSet>))::type;
};
}  // namespace detail

// The union of two plugin sets (for example two families of plugins).
template <class A, class B>
using merge_plugin_sets = typename detail::merge_sets<A, B>::type;

}  // namespace ftsense
