#include "planning/robot/chain_json.h"

#include <stdexcept>

namespace planning {

ChainDescription ReadChainDescription(const base::JsonNode& node) {
  node.CheckKeys({"name", "closed", "points"});
  ChainDescription c;
  c.where = node.Where();
  c.name = node.At("name").String();
  c.closed = node.Bool("closed", false);
  const base::JsonNode pts = node.At("points");
  if (pts.Size() < 2) pts.Fail("a chain needs at least 2 points");
  c.point_local.resize(3, static_cast<Eigen::Index>(pts.Size()));
  for (size_t k = 0; k < pts.Size(); ++k) {
    const base::JsonNode p = pts.At(k);
    p.CheckKeys({"link", "xyz"});
    const base::JsonNode link = p.At("link");
    c.links.push_back(link.String());
    c.link_where.push_back(link.Where());
    c.point_local.col(static_cast<Eigen::Index>(k)) = p.Vec3("xyz", Eigen::Vector3d::Zero());
  }
  return c;
}

ChainSpec ResolveChain(const ChainDescription& chain, const Robot& robot) {
  for (const ChainSpec& other : robot.chains) {
    if (other.name == chain.name) {
      throw std::invalid_argument(chain.where + ".name: duplicate chain '" + chain.name + "'");
    }
  }
  std::vector<std::string> names;
  for (const Link& l : robot.links) names.push_back(l.name);
  ChainSpec spec;
  spec.name = chain.name;
  spec.closed = chain.closed;
  spec.point_local = chain.point_local;
  for (size_t k = 0; k < chain.links.size(); ++k) {
    int index = -1;
    for (size_t l = 0; l < names.size(); ++l) {
      if (names[l] == chain.links[k]) index = static_cast<int>(l);
    }
    if (index < 0) {
      std::string hint = base::DidYouMean(chain.links[k], names);
      if (hint.empty()) {  // nothing close: list the links (at most 40)
        hint = " (links: ";
        for (size_t l = 0; l < names.size() && l < 40; ++l)
          hint.append(l ? ", " : "").append(names[l]);
        if (names.size() > 40)
          hint.append(", ... (").append(std::to_string(names.size() - 40)).append(" more)");
        hint.append(")");
      }
      throw std::invalid_argument(chain.link_where[k] + ": unknown link '" + chain.links[k] + "'" +
                                  hint);
    }
    spec.point_link.push_back(index);
  }
  return spec;
}

}  // namespace planning
