// URDF robot descriptions to chains (see urdf.h): urdfdom parses, its console_bridge log is
// captured and reworded, and the chain is walked from the tool link up to the base link.
#include "kinematics/urdf.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <numbers>
#include <set>
#include <sstream>
#include <vector>

namespace prs::kinematics {

namespace {

// Collects urdfdom's log lines instead of printing them.
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(text);
  }
  std::vector<std::string> errors;
};

// console_bridge's handler and level are process-wide: one parse at a time installs ours.
std::mutex& LogMutex() {
  static std::mutex mutex;
  return mutex;
}

bool IsDigits(const std::string& s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

// A C++ source location such as "/build/urdfdom/src/joint.cpp:123:".
bool IsSourceFile(std::string word) {
  while (!word.empty() &&
         (word.back() == ':' || std::isdigit(static_cast<unsigned char>(word.back())))) {
    word.pop_back();
  }
  for (const char* suffix : {".cpp", ".cc", ".cxx", ".h", ".hpp"}) {
    const std::string ending = suffix;
    if (word.size() > ending.size() &&
        word.compare(word.size() - ending.size(), ending.size(), ending) == 0) {
      return true;
    }
  }
  return false;
}

bool StartsWithNoCase(const std::string& text, const std::string& prefix) {
  if (text.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(text[i])) != prefix[i]) return false;
  }
  return true;
}

// A log line without console_bridge's decorations ("Error:", "at line 12 in file.cpp") or C++
// source locations, words joined by single spaces.
std::string CleanMessage(const std::string& text) {
  std::vector<std::string> words;
  std::istringstream in(text);
  for (std::string word; in >> word;) words.push_back(word);
  std::string clean;
  for (size_t i = 0; i < words.size(); ++i) {
    if (i + 4 < words.size() && words[i] == "at" && words[i + 1] == "line" &&
        IsDigits(words[i + 2]) && words[i + 3] == "in") {
      i += 4;  // "at line N in FILE"
      continue;
    }
    if (IsSourceFile(words[i])) continue;
    clean += (clean.empty() ? "" : " ") + words[i];
  }
  for (bool stripped = true; stripped;) {
    stripped = false;
    for (const char* prefix :
         {"console_bridge:", "console_bridge", "error:", "warning:", "warn:", "info:", "debug:"}) {
      if (StartsWithNoCase(clean, prefix)) {
        const size_t rest = clean.find_first_not_of(' ', std::string(prefix).size());
        clean = rest == std::string::npos ? "" : clean.substr(rest);
        stripped = true;
      }
    }
  }
  return clean;
}

// urdfdom's model, or its reasons for refusing the text (one sentence, cleaned).
urdf::ModelInterfaceSharedPtr ParseQuietly(const std::string& xml_text, std::string* reason) {
  std::lock_guard<std::mutex> lock(LogMutex());
  CapturingHandler handler;
  const console_bridge::LogLevel level = console_bridge::getLogLevel();
  console_bridge::useOutputHandler(&handler);
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
  urdf::ModelInterfaceSharedPtr model;
  std::string thrown;
  try {
    model = urdf::parseURDF(xml_text);
  } catch (const std::exception& e) {
    thrown = e.what();
  } catch (...) {
    thrown = "an unknown error";
  }
  console_bridge::restorePreviousOutputHandler();
  console_bridge::setLogLevel(level);
  std::vector<std::string> reasons;
  for (const std::string& e : handler.errors) {
    const std::string clean = CleanMessage(e);
    if (!clean.empty() && std::find(reasons.begin(), reasons.end(), clean) == reasons.end()) {
      reasons.push_back(clean);
    }
  }
  if (!thrown.empty()) reasons.push_back(CleanMessage(thrown));
  reasons.erase(std::remove(reasons.begin(), reasons.end(), ""), reasons.end());
  // urdfdom logs the specific problem first, then how it gave up ("joint xml is not
  // initialized correctly", "failed to parse joint"): the first line says it.
  *reason = reasons.empty() ? "urdfdom gave no reason" : reasons.front();
  return model;
}

// Levenshtein distance, for "did you mean".
int CalcEditDistance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitute});
    }
  }
  return row[b.size()];
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "'" : ", '") + n + "'";
  return text;
}

urdf::LinkConstSharedPtr FindLink(const urdf::ModelInterface& model, const std::string& name,
                                  const std::string& label, const char* role) {
  if (urdf::LinkConstSharedPtr link = model.getLink(name)) return link;
  std::vector<std::string> names;
  for (const auto& [link_name, link] : model.links_) names.push_back(link_name);
  std::string message = label + ": no link named '" + name + "' (the " + role + " link)";
  std::string best;
  int best_distance = std::max<int>(2, static_cast<int>(name.size()) / 3) + 1;
  for (const std::string& n : names) {
    const int d = CalcEditDistance(name, n);
    if (d < best_distance) best = n, best_distance = d;
  }
  message += "; its links are " + JoinNames(names);
  if (!best.empty()) message += "; did you mean '" + best + "'?";
  throw KinematicsError(message);
}

// The only link without children below `base`.
urdf::LinkConstSharedPtr FindOnlyLeaf(const urdf::LinkConstSharedPtr& base,
                                      const std::string& label) {
  std::vector<urdf::LinkConstSharedPtr> leaves, stack = {base};
  while (!stack.empty()) {
    const urdf::LinkConstSharedPtr link = stack.back();
    stack.pop_back();
    if (link->child_links.empty()) leaves.push_back(link);
    for (const urdf::LinkSharedPtr& child : link->child_links) stack.push_back(child);
  }
  if (leaves.size() == 1) return leaves.front();
  std::vector<std::string> names;
  for (const auto& leaf : leaves) names.push_back(leaf->name);
  std::sort(names.begin(), names.end());
  throw KinematicsError(label + ": link '" + base->name + "' has " + std::to_string(leaves.size()) +
                        " leaf links (" + JoinNames(names) +
                        "), so the tool is ambiguous: name the tool link");
}

// urdfdom builds its links with shared pointers both ways (a link holds its child links and
// joints and its parent joint), so a description whose joints make a loop leaves a cycle that
// no owner frees. Cut every link's pointers when the model is done with.
class ModelReleaser {
 public:
  explicit ModelReleaser(urdf::ModelInterfaceSharedPtr model) : model_(std::move(model)) {}
  ~ModelReleaser() {
    if (!model_) return;
    for (auto& [name, link] : model_->links_) {
      link->child_links.clear();
      link->child_joints.clear();
      link->parent_joint.reset();
    }
  }
  ModelReleaser(const ModelReleaser&) = delete;
  ModelReleaser& operator=(const ModelReleaser&) = delete;

 private:
  urdf::ModelInterfaceSharedPtr model_;
};

// Refuses links that are not a tree: a link that is the child of two joints, or one from which
// following parents never reaches the root (urdfdom accepts a joint whose parent and child are
// the same link, for one). Walks over the links are then finite.
void CheckIsTree(const urdf::ModelInterface& model, const std::string& label) {
  const size_t links = model.links_.size();
  for (const auto& [name, link] : model.links_) {
    for (const urdf::LinkSharedPtr& child : link->child_links) {
      if (child && child->getParent() != link) {
        throw KinematicsError(label + ": link '" + child->name + "' is the child of more than one "
                              "joint (of link '" + name + "' and of link '" +
                              (child->getParent() ? child->getParent()->name : std::string("?")) +
                              "'); the joints must connect the links as a tree");
      }
    }
  }
  for (const auto& [name, link] : model.links_) {
    urdf::LinkConstSharedPtr at = link;
    for (size_t steps = 0; at && at->getParent(); ++steps) {
      if (steps > links) {
        throw KinematicsError(label + ": the joints do not connect the links as a tree: going up "
                              "from link '" + name + "' runs round a loop; each link needs one "
                              "parent, and no link may be its own ancestor");
      }
      at = at->getParent();
    }
  }
}

// A joint of the document as written: from its parent link to its child link.
struct JointEdge {
  std::string joint;
  std::string child;
};

// "'a' -> 'b' -> 'c' -> 'a'", the middle of a long loop left out.
std::string FormatLoop(const std::vector<std::string>& links) {
  constexpr size_t kShownAtEachEnd = 4;
  std::string text;
  for (size_t i = 0; i < links.size(); ++i) {
    if (i == kShownAtEachEnd && links.size() > 2 * kShownAtEachEnd + 1) {
      text += " -> ... (" + std::to_string(links.size() - 2 * kShownAtEachEnd) + " more)";
      i = links.size() - kShownAtEachEnd;
    }
    text += (i == 0 ? "'" : " -> '") + links[i] + "'";
  }
  return text;
}

// Refuses joints that make a loop (a link that is its own ancestor), read from the XML itself
// before urdfdom sees it: urdfdom then finds no root link and says only that the robot "is not
// a valid tree", naming no link. The walk starts at the links that are no joint's child, then
// at the others in document order; the joint that leads back to a link on the current path
// closes the loop, and is named with that link.
void CheckJointsMakeNoLoop(const TiXmlElement& robot, const std::string& label) {
  std::map<std::string, std::vector<JointEdge>> children;  // by parent link, document order
  std::vector<std::string> parents;                        // in document order, once each
  std::set<std::string> child_links;
  for (const TiXmlElement* j = robot.FirstChildElement("joint"); j;
       j = j->NextSiblingElement("joint")) {
    const TiXmlElement* parent = j->FirstChildElement("parent");
    const TiXmlElement* child = j->FirstChildElement("child");
    const char* parent_link = parent ? parent->Attribute("link") : nullptr;
    const char* child_link = child ? child->Attribute("link") : nullptr;
    if (!parent_link || !child_link) continue;  // urdfdom says what is missing
    const char* name = j->Attribute("name");
    auto [it, added] = children.try_emplace(parent_link);
    if (added) parents.push_back(parent_link);
    it->second.push_back({name ? name : "", child_link});
    child_links.insert(child_link);
  }
  std::vector<std::string> starts;
  for (const std::string& link : parents) {
    if (!child_links.count(link)) starts.push_back(link);
  }
  starts.insert(starts.end(), parents.begin(), parents.end());
  enum class Mark { kOnPath, kDone };
  std::map<std::string, Mark> marks;
  for (const std::string& start : starts) {
    if (marks.count(start)) continue;
    // Depth first, without recursion (a fuzzed file may chain thousands of links): each
    // entry is a link on the path and the next of its joints to follow.
    std::vector<std::pair<std::string, size_t>> path = {{start, 0}};
    marks[start] = Mark::kOnPath;
    while (!path.empty()) {
      auto& [link, next] = path.back();
      const auto found = children.find(link);
      if (found == children.end() || next >= found->second.size()) {
        marks[link] = Mark::kDone;
        path.pop_back();
        continue;
      }
      const JointEdge& edge = found->second[next++];
      const auto mark = marks.find(edge.child);
      if (mark == marks.end()) {
        marks[edge.child] = Mark::kOnPath;
        path.push_back({edge.child, 0});
        continue;
      }
      if (mark->second == Mark::kDone) continue;
      // edge.child is on the path: the links from it down to `link` and back make the loop.
      std::vector<std::string> loop;
      for (const auto& [on_path, unused] : path) {
        if (!loop.empty() || on_path == edge.child) loop.push_back(on_path);
      }
      loop.push_back(edge.child);
      const std::string closing =
          edge.child == link
              ? "joint '" + edge.joint + "' makes link '" + link + "' its own child"
              : "joint '" + edge.joint + "' makes link '" + edge.child + "' a child of link '" +
                    link + "', which is below it already";
      throw KinematicsError(label + ": the joints do not connect the links as a tree: " + closing +
                            ", closing the loop " + FormatLoop(loop) +
                            "; each link needs one parent, and no link may be its own ancestor");
    }
  }
}

// The joints from base down to tool, in that order.
std::vector<urdf::JointConstSharedPtr> FindPath(const urdf::LinkConstSharedPtr& base,
                                                const urdf::LinkConstSharedPtr& tool,
                                                const std::string& label) {
  std::vector<urdf::JointConstSharedPtr> path;
  std::string walked = "'" + tool->name + "'";
  for (urdf::LinkConstSharedPtr link = tool; link != base;) {
    if (!link->parent_joint) {
      throw KinematicsError(label + ": the tool link '" + tool->name +
                            "' is not downstream of the base link '" + base->name +
                            "' (from the tool up to the root: " + walked + ")");
    }
    path.push_back(link->parent_joint);
    link = link->getParent();
    walked += " <- '" + link->name + "'";
  }
  std::reverse(path.begin(), path.end());
  return path;
}

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << pose.position.x, pose.position.y, pose.position.z;
  X.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return X;
}

const char* DescribeType(int type) {
  switch (type) {
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    default:
      return "of unknown type";
  }
}

// A movable joint of the chain, its frame at X_PJ.
Joint MakeJoint(const urdf::Joint& j, const Eigen::Isometry3d& X_PJ, const std::string& label) {
  const std::string where = label + ": joint '" + j.name + "'";
  Joint joint;
  joint.name = j.name;
  joint.type = j.type == urdf::Joint::PRISMATIC ? JointType::kPrismatic : JointType::kRevolute;
  joint.X_PJ = X_PJ;
  const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
  if (!(axis.norm() > 1e-12)) throw KinematicsError(where + " has a zero axis");
  joint.axis_J = axis.normalized();
  if (j.mimic) {
    throw KinematicsError(where + " mimics joint '" + j.mimic->joint_name +
                          "'; mimic joints cannot be on an arm's chain");
  }
  if (j.type == urdf::Joint::CONTINUOUS) {
    joint.lower = -std::numbers::pi;
    joint.upper = std::numbers::pi;
    return joint;
  }
  if (!j.limits) throw KinematicsError(where + " has no <limit> element");
  joint.lower = j.limits->lower;
  joint.upper = j.limits->upper;
  if (joint.lower > joint.upper) {
    char limits[96];
    std::snprintf(limits, sizeof limits, " has its lower limit (%g) above its upper limit (%g)",
                  joint.lower, joint.upper);
    throw KinematicsError(where + limits);
  }
  return joint;
}

Chain BuildChain(const std::vector<urdf::JointConstSharedPtr>& path, const std::string& base,
                 const std::string& tool, const std::string& label) {
  Chain chain;
  chain.name = label;
  Eigen::Isometry3d X_fixed = Eigen::Isometry3d::Identity();  // since the last movable joint
  for (const urdf::JointConstSharedPtr& j : path) {
    const Eigen::Isometry3d X_origin = ToIsometry(j->parent_to_joint_origin_transform);
    switch (j->type) {
      case urdf::Joint::FIXED:
        X_fixed = X_fixed * X_origin;
        break;
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
      case urdf::Joint::PRISMATIC:
        chain.joints.push_back(MakeJoint(*j, X_fixed * X_origin, label));
        X_fixed = Eigen::Isometry3d::Identity();
        break;
      default:
        throw KinematicsError(label + ": joint '" + j->name + "' on the chain from '" + base +
                              "' to '" + tool + "' is " + DescribeType(j->type) +
                              "; an arm's chain can have only revolute, continuous, prismatic "
                              "and fixed joints");
    }
  }
  chain.X_LastTool = X_fixed;
  if (chain.joints.empty()) {
    throw KinematicsError(label + ": the chain from '" + base + "' to '" + tool +
                          "' has no movable joint");
  }
  return chain;
}

}  // namespace

// The byte offset of the first thing in `text` that is not UTF-8 (or a NUL byte), or npos.
// TinyXML 2.6.2 trusts a multi-byte sequence's lead byte and reads past the end of a text that
// stops inside one, so a description is checked before any XML parser sees it.
size_t FindInvalidUtf8(const std::string& text) {
  for (size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte == 0) return i;
    const int length = byte < 0x80 ? 1 : (byte >> 5) == 0x6 ? 2 : (byte >> 4) == 0xE ? 3
                     : (byte >> 3) == 0x1E ? 4 : 0;
    if (length == 0 || i + length > text.size()) return i;
    for (int k = 1; k < length; ++k) {
      if ((static_cast<unsigned char>(text[i + k]) >> 6) != 0x2) return i;
    }
    i += length;
  }
  return std::string::npos;
}

Chain LoadUrdfChain(const std::string& xml_text, const std::string& file_label,
                    const std::string& base_link, const std::string& tool_link) {
  if (const size_t bad = FindInvalidUtf8(xml_text); bad != std::string::npos) {
    const auto line = 1 + std::count(xml_text.begin(), xml_text.begin() + bad, '\n');
    throw KinematicsError(file_label + ": not UTF-8 text (line " + std::to_string(line) + ", byte " +
                          std::to_string(bad + 1) + "): a URDF file is an XML document in UTF-8");
  }
  TiXmlDocument document;
  document.Parse(xml_text.c_str());
  if (document.Error()) {
    // TinyXML's descriptions read "Error reading end tag." or "Error document empty.": without
    // the "Error" and the period, and located when TinyXML knows where.
    std::string description = CleanMessage(document.ErrorDesc());
    if (description.rfind("Error ", 0) == 0) description.erase(0, 6);
    if (!description.empty() && description.back() == '.') description.pop_back();
    if (description == "document empty") description = "no XML element in it";
    std::string where;
    if (document.ErrorRow() > 0) {
      where = " (line " + std::to_string(document.ErrorRow()) + ", column " +
              std::to_string(document.ErrorCol()) + ")";
    }
    throw KinematicsError(file_label + ": not an XML document: " + description + where);
  }
  const TiXmlElement* root = document.RootElement();
  if (!root || root->ValueStr() != "robot") {
    throw KinematicsError(file_label + ": not a URDF robot description: the top element is <" +
                          (root ? root->ValueStr() : std::string()) + ">, not <robot>");
  }
  CheckJointsMakeNoLoop(*root, file_label);
  std::string reason;
  const urdf::ModelInterfaceSharedPtr model = ParseQuietly(xml_text, &reason);
  if (!model) throw KinematicsError(file_label + ": not a valid URDF: " + reason);
  const ModelReleaser releaser(model);
  CheckIsTree(*model, file_label);
  const urdf::LinkConstSharedPtr base =
      base_link.empty() ? model->getRoot() : FindLink(*model, base_link, file_label, "base");
  if (!base) throw KinematicsError(file_label + ": the URDF has no root link");
  const urdf::LinkConstSharedPtr tool = tool_link.empty()
                                            ? FindOnlyLeaf(base, file_label)
                                            : FindLink(*model, tool_link, file_label, "tool");
  Chain chain = BuildChain(FindPath(base, tool, file_label), base->name, tool->name, file_label);
  ValidateChain(chain);
  return chain;
}

}  // namespace prs::kinematics
