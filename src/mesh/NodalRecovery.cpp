#include "mesh/NodalRecovery.hpp"

namespace stentor {

std::vector<double> recover_at_nodes(const Mesh& mesh, const std::vector<double>& cell_values, int k,
                                     const std::vector<double>& volume) {
  const std::size_t nn = mesh.num_nodes(), kk = static_cast<std::size_t>(k);
  std::vector<double> sum(nn * kk, 0.0), weight(nn, 0.0);
  std::vector<int> body(nn, -1);
  for (std::size_t b = 0; b < mesh.volumes.size(); ++b) {
    const CellBlock& blk = mesh.volumes[b];
    const auto npc = static_cast<std::size_t>(blk.nodes_per_cell);
    for (std::size_t i = 0; i < blk.num_cells(); ++i) {
      const auto c = static_cast<std::size_t>(blk.cell_id[i]);
      for (std::size_t a = 0; a < npc; ++a) {
        const auto n = static_cast<std::size_t>(blk.conn[i * npc + a]);
        if (body[n] < 0) body[n] = static_cast<int>(b);
        if (body[n] != static_cast<int>(b)) continue;
        weight[n] += volume[c];
        for (std::size_t j = 0; j < kk; ++j) sum[n * kk + j] += volume[c] * cell_values[c * kk + j];
      }
    }
  }
  for (std::size_t n = 0; n < nn; ++n)
    for (std::size_t j = 0; j < kk; ++j) sum[n * kk + j] = weight[n] > 0.0 ? sum[n * kk + j] / weight[n] : 0.0;
  return sum;
}

}  // namespace stentor
