#include "particles/particles.hpp"

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
  auto& [s2, s1, s4, su, sb] = scratch;
  permute_array(x, begin, order, s2);
  permute_array(x0, begin, order, s2);
  permute_array(v, begin, order, s2);
  permute_array(mass, begin, order, s1);
  permute_array(volume0, begin, order, s1);
  permute_array(J, begin, order, s1);
  permute_array(pressure, begin, order, s1);
  permute_array(F, begin, order, s4);
  permute_array(stress, begin, order, s4);
  permute_array(C, begin, order, s4);
  permute_array(id, begin, order, su);
  permute_array(body, begin, order, sb);
}

}  // namespace bsmpm
