#include "particles/particles.hpp"

#include <type_traits>

namespace bsmpm {

namespace {
template <class T>
void permute_array(std::vector<T>& a, std::size_t begin, const std::vector<std::uint32_t>& order,
                   std::vector<T>& scratch) {
  scratch.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) scratch[k] = a[begin + order[k]];
  for (std::size_t k = 0; k < order.size(); ++k) a[begin + k] = scratch[k];
}
}  // namespace

void Particles::permute(std::size_t begin, const std::vector<std::uint32_t>& order, PermuteScratch& scratch) {
  for_each_array([&](auto& a) {
    using Element = typename std::decay_t<decltype(a)>::value_type;
    permute_array(a, begin, order, scratch.of<Element>());
  });
}

}  // namespace bsmpm
