#include "planning/robot/internal/collada_check.h"

#include <tinyxml.h>

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/numbers.h"

namespace planning::internal {
namespace {

// What one <node> holds before expansion.
struct NodeInfo {
  std::vector<std::string> children;  // ids of child nodes and of instanced nodes
  double triangles = 0.0;             // its own <instance_geometry>s
};

double GeometryTriangles(const TiXmlElement* geometry) {
  double n = 0.0;
  for (const TiXmlElement* mesh = geometry->FirstChildElement(); mesh;
       mesh = mesh->NextSiblingElement()) {
    for (const TiXmlElement* p = mesh->FirstChildElement(); p; p = p->NextSiblingElement()) {
      const std::string tag = p->Value();
      if (tag != "triangles" && tag != "polylist" && tag != "polygons" && tag != "trifans" &&
          tag != "tristrips") {
        continue;
      }
      const char* count = p->Attribute("count");
      const std::optional<long long> c = count ? base::ParseInteger(count) : std::nullopt;
      if (c && *c > 0) n += static_cast<double>(*c);
    }
  }
  return n;
}

std::string Id(const TiXmlElement* e) {
  const char* id = e->Attribute("id");
  return id ? id : "";
}

std::string Target(const TiXmlElement* e) {
  const char* url = e->Attribute("url");
  if (!url || url[0] != '#') return "";
  return url + 1;
}

class Graph {
 public:
  Graph(const TiXmlDocument& doc, const std::string& path) : path_(path) {
    const TiXmlElement* root = doc.RootElement();
    if (!root) return;
    for (const TiXmlElement* lib = root->FirstChildElement("library_geometries"); lib;
         lib = lib->NextSiblingElement("library_geometries")) {
      for (const TiXmlElement* g = lib->FirstChildElement("geometry"); g;
           g = g->NextSiblingElement("geometry")) {
        geometry_triangles_[Id(g)] = GeometryTriangles(g);
      }
    }
    for (const TiXmlElement* lib = root->FirstChildElement(); lib;
         lib = lib->NextSiblingElement()) {
      const std::string tag = lib->Value();
      if (tag == "library_nodes") {
        for (const TiXmlElement* n = lib->FirstChildElement("node"); n;
             n = n->NextSiblingElement("node")) {
          Add(n);
        }
      } else if (tag == "library_visual_scenes") {
        for (const TiXmlElement* vs = lib->FirstChildElement("visual_scene"); vs;
             vs = vs->NextSiblingElement("visual_scene")) {
          for (const TiXmlElement* n = vs->FirstChildElement("node"); n;
               n = n->NextSiblingElement("node")) {
            roots_.push_back(Add(n));
          }
        }
      }
    }
  }

  // Expanded instances and triangles of every visual scene root; throws on a cycle.
  void Check(std::size_t max_triangles) {
    double instances = 0.0, triangles = 0.0;
    for (const std::string& r : roots_) {
      const auto [i, t] = Expand(r);
      instances += i;
      triangles += t;
    }
    if (instances > static_cast<double>(kMaxColladaInstances)) {
      throw std::invalid_argument(path_ + ": COLLADA scene expands to " +
                                  base::FormatShortest(instances) +
                                  " node instances, more than the limit of " +
                                  std::to_string(kMaxColladaInstances));
    }
    if (triangles > static_cast<double>(max_triangles)) {
      throw std::invalid_argument(path_ + ": COLLADA scene expands to " +
                                  base::FormatShortest(triangles) +
                                  " triangles, more than the limit of " +
                                  std::to_string(max_triangles));
    }
  }

 private:
  // Registers `n` and its nested nodes; returns the key of `n`.
  std::string Add(const TiXmlElement* n) {
    std::string key = Id(n);
    if (key.empty()) key = "(unnamed node, line " + std::to_string(n->Row()) + ")";
    NodeInfo& info = nodes_[key];
    for (const TiXmlElement* c = n->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Value();
      if (tag == "node") {
        info.children.push_back(Add(c));
      } else if (tag == "instance_node") {
        info.children.push_back(Target(c));
      } else if (tag == "instance_geometry") {
        const auto g = geometry_triangles_.find(Target(c));
        if (g != geometry_triangles_.end()) info.triangles += g->second;
      }
    }
    return key;
  }

  // (instances, triangles) of node `key` expanded: memoised, depth-first with a cycle check.
  std::pair<double, double> Expand(const std::string& key) {
    if (const auto done = done_.find(key); done != done_.end()) return done->second;
    if (std::find(stack_.begin(), stack_.end(), key) != stack_.end()) {
      std::string cycle;
      for (auto it = std::find(stack_.begin(), stack_.end(), key); it != stack_.end(); ++it) {
        cycle += "'" + *it + "' -> ";
      }
      throw std::invalid_argument(path_ + ": COLLADA node '" + key +
                                  "' instances itself (" + cycle + "'" + key + "')");
    }
    const auto node = nodes_.find(key);
    if (node == nodes_.end()) return {0.0, 0.0};  // an unknown url: assimp skips it
    stack_.push_back(key);
    double instances = 1.0, triangles = node->second.triangles;
    for (const std::string& c : node->second.children) {
      const auto [i, t] = Expand(c);
      instances = std::min(instances + i, 1e300);
      triangles = std::min(triangles + t, 1e300);
    }
    stack_.pop_back();
    return done_[key] = {instances, triangles};
  }

  std::string path_;
  std::map<std::string, double> geometry_triangles_;
  std::map<std::string, NodeInfo> nodes_;
  std::vector<std::string> roots_;
  std::map<std::string, std::pair<double, double>> done_;
  std::vector<std::string> stack_;
};

}  // namespace

void CheckColladaStructure(const std::string& xml, const std::string& path,
                           std::size_t max_triangles) {
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  if (doc.Error()) {
    throw std::invalid_argument(path + ":" + std::to_string(doc.ErrorRow()) +
                                ": XML error: " + doc.ErrorDesc());
  }
  Graph graph(doc, path);
  graph.Check(max_triangles);
}

}  // namespace planning::internal
