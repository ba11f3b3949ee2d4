#include "lemon_matching.hpp"

#include <lemon/matching.h>
#include <lemon/smart_graph.h>

namespace ccbuild::planner::detail {

SparseMatching max_weight_perfect_matching(int nodes, const std::vector<std::pair<int, int>>& edges,
                                           const std::vector<std::int64_t>& weights) {
  using Graph = lemon::SmartGraph;
  using Weights = Graph::EdgeMap<std::int64_t>;
  using Matcher = lemon::MaxWeightedPerfectMatching<Graph, Weights>;
  Graph graph;
  graph.reserveNode(nodes);
  graph.reserveEdge(static_cast<int>(edges.size()));
  for (int i = 0; i < nodes; ++i) graph.addNode();
  Weights weight(graph);
  for (std::size_t e = 0; e < edges.size(); ++e)
    weight[graph.addEdge(graph.nodeFromId(edges[e].first), graph.nodeFromId(edges[e].second))] =
        weights[e];
  Matcher matcher(graph, weight);
  SparseMatching out;
  out.dual_scale = Matcher::dualScale;
  out.perfect = matcher.run();
  if (!out.perfect) return out;
  out.mate.resize(nodes);
  out.node_potential.resize(nodes);
  for (int i = 0; i < nodes; ++i) {
    const Graph::Node node = graph.nodeFromId(i);
    out.mate[i] = graph.id(matcher.mate(node));
    out.node_potential[i] = matcher.nodeValue(node);
  }
  out.blossom_value.resize(matcher.blossomNum());
  out.blossom_nodes.resize(matcher.blossomNum());
  for (int b = 0; b < matcher.blossomNum(); ++b) {
    out.blossom_value[b] = matcher.blossomValue(b);
    for (Matcher::BlossomIt it(matcher, b); it != lemon::INVALID; ++it)
      out.blossom_nodes[b].push_back(graph.id(static_cast<Graph::Node>(it)));
  }
  return out;
}

}  // namespace ccbuild::planner::detail
