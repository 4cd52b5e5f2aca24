#include "mesh/NodalRecovery.hpp"

namespace stentor {

namespace {

// The recovery on the nodes [begin, end): `each_cell(add)` calls add(b, nodes, npc, volume,
// values) for every cell (of volume block b, with the npc nodes `nodes`) to take into
// account, in the summation order.
template <class EachCell>
std::vector<double> recover(std::size_t begin, std::size_t end, std::size_t kk, EachCell each_cell) {
  const std::size_t nn = end - begin;
  std::vector<double> sum(nn * kk, 0.0), weight(nn, 0.0);
  std::vector<int> body(nn, -1);
  each_cell([&](std::size_t b, const GId* nodes, std::size_t npc, double volume, const double* values) {
    for (std::size_t a = 0; a < npc; ++a) {
      const auto g = static_cast<std::size_t>(nodes[a]);
      if (g < begin || g >= end) continue;
      const std::size_t n = g - begin;
      if (body[n] < 0) body[n] = static_cast<int>(b);
      if (body[n] != static_cast<int>(b)) continue;
      weight[n] += volume;
      for (std::size_t j = 0; j < kk; ++j) sum[n * kk + j] += volume * values[j];
    }
  });
  for (std::size_t n = 0; n < nn; ++n)
    for (std::size_t j = 0; j < kk; ++j) sum[n * kk + j] = weight[n] > 0.0 ? sum[n * kk + j] / weight[n] : 0.0;
  return sum;
}

}  // namespace

std::vector<double> recover_at_nodes(const Mesh& mesh, const std::vector<double>& cell_values, int k,
                                     const std::vector<double>& volume) {
  const auto kk = static_cast<std::size_t>(k);
  return recover(0, mesh.num_nodes(), kk, [&](auto&& add) {
    for (std::size_t b = 0; b < mesh.volumes.size(); ++b) {
      const CellBlock& blk = mesh.volumes[b];
      const auto npc = static_cast<std::size_t>(blk.nodes_per_cell);
      for (std::size_t i = 0; i < blk.num_cells(); ++i) {
        const auto c = static_cast<std::size_t>(blk.cell_id[i]);
        add(b, &blk.conn[i * npc], npc, volume[c], &cell_values[c * kk]);
      }
    }
  });
}

std::vector<double> recover_at_node_rows(std::size_t begin, std::size_t end, const CellNodes& cells,
                                         const std::vector<double>& cell_values, int k, const std::vector<double>& volume) {
  const auto kk = static_cast<std::size_t>(k);
  return recover(begin, end, kk, [&](auto&& add) {
    for (std::size_t j = 0; j < cells.size(); ++j)
      add(static_cast<std::size_t>(cells.block[j]), cells.nodes.data() + cells.first[j], cells.first[j + 1] - cells.first[j],
          volume[j], &cell_values[j * kk]);
  });
}

}  // namespace stentor
