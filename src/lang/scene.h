// What one run of a program produces: a scene (placed objects and parameters), or the reason
// the attempt was rejected. Plain data, read by the sampler and the output writers.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "lang/source.h"
#include "lang/value.h"

namespace prs::lang {

struct ClassInfo;
struct CompiledProgram;
struct Expr;

/// An object's properties in definition order. Copies share one list until one of them is
/// changed (copy on write), so an object a sampler copies unchanged into every scene
/// (SceneObject::fixed_id) costs no copy of its properties, and a copy of a template
/// (SceneObject::template_id) holds only its one changed entry, its position (SetValue). Read
/// it as a vector of (name, value) pairs.
class PropertyList {
 public:
  using Entry = std::pair<std::string, Value>;
  PropertyList() = default;
  PropertyList(std::initializer_list<Entry> entries)
      : entries_(std::make_shared<std::vector<Entry>>(entries)) {}

  size_t size() const { return entries_ ? entries_->size() : 0; }
  bool empty() const { return size() == 0; }
  const Entry& operator[](size_t i) const {
    return replaced_ && i == replaced_slot_ ? *replaced_ : (*entries_)[i];
  }

  /// Entries in order, this list's replaced entry in its place.
  class Iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Entry;
    using difference_type = std::ptrdiff_t;
    using pointer = const Entry*;
    using reference = const Entry&;
    Iterator(const PropertyList* list, size_t i) : list_(list), i_(i) {}
    const Entry& operator*() const { return (*list_)[i_]; }
    const Entry* operator->() const { return &(*list_)[i_]; }
    Iterator& operator++() {
      ++i_;
      return *this;
    }
    Iterator operator++(int) { return Iterator(list_, i_++); }
    bool operator==(const Iterator& other) const { return i_ == other.i_; }
    bool operator!=(const Iterator& other) const { return i_ != other.i_; }

   private:
    const PropertyList* list_;
    size_t i_;
  };
  Iterator begin() const { return Iterator(this, 0); }
  Iterator end() const { return Iterator(this, size()); }

  /// The entries for writing: this list's own, copied first if another list shares them.
  std::vector<Entry>& Mutable() {
    if (!entries_) {
      entries_ = std::make_shared<std::vector<Entry>>();
    } else if (entries_.use_count() > 1) {
      entries_ = std::make_shared<std::vector<Entry>>(*entries_);
    }
    if (replaced_) {
      (*entries_)[replaced_slot_] = std::move(*replaced_);
      replaced_.reset();
    }
    return *entries_;
  }

  /// Sets entry i's value. While the entries are shared, the first entry so set is held by this
  /// list alone and the rest stays shared; a second one copies the list (Mutable).
  void SetValue(size_t i, Value value) {
    if (replaced_ && i == replaced_slot_) {
      replaced_->second = std::move(value);
    } else if (!replaced_ && entries_.use_count() > 1) {
      replaced_.emplace((*entries_)[i].first, std::move(value));
      replaced_slot_ = i;
    } else {
      Mutable()[i].second = std::move(value);
    }
  }

 private:
  std::shared_ptr<std::vector<Entry>> entries_;
  std::optional<Entry> replaced_;  // entry `replaced_slot_`, when set: this list's own value
  size_t replaced_slot_ = 0;
};

struct SceneObject {
  std::optional<std::string> name;  // the first variable it was bound to; none if anonymous
  const ClassInfo* cls = nullptr;
  SourceSpan span;                  // where it was created
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();
  Eigen::Quaterniond R_WO = Eigen::Quaterniond::Identity();
  Eigen::Vector3d dimensions = Eigen::Vector3d::Zero();  // width, length, height (0 for points)
  bool allow_collisions = false;
  /// Its shape when the `shape` property is a mesh (`Mesh("mug.obj")`), else null (a box). The
  /// mesh is `mesh_scale` times the file's size; `dimensions` is its scaled bounding box.
  /// A built-in shape (`Cylinder()`, ...) sets `primitive`, and `mesh` to its polytope at the
  /// object's size (shapes/primitive.h, scale 1) once width, length and height are known; a
  /// primitive with a zero size stays a (flat) box, which holds it.
  std::shared_ptr<const shapes::MeshShape> mesh;
  double mesh_scale = 1;
  std::optional<shapes::Primitive> primitive;
  bool fixed = false;  // the same in every scene (ObjectPlan::object_fixed)
  /// Nonzero for an object a sampler keeps and copies unchanged into later scenes (RunCache::
  /// fixed_objects): objects with the same id are equal in every field, so what is made from
  /// one (its JSON text) serves them all. Ids are never reused within a process.
  uint64_t fixed_id = 0;
  /// Nonzero for an object copied from a creation site's template (RunCache::object_templates;
  /// ObjectPlan::template_fixed): objects with the same id are equal in every field but their
  /// name, span, p_WO and "position" property. Drawn from the same counter as fixed_id.
  uint64_t template_id = 0;
  /// Every property in definition order, position and orientation included.
  PropertyList properties;

  const Value* FindProperty(const std::string& property) const;
  /// The object's display name: its variable, or "Class#index".
  std::string DisplayName(int index) const;
};

/// A region an object's position was drawn from, kept only when RunOptions::record_regions is
/// set (for pictures: `prs render --show-regions`). Also a camera's view (its frustum within
/// the workspace) for the view specifiers that name it.
struct PlacedRegion {
  int object = -1;      // the object placed in it, or the camera whose view it is
  std::string what;     // "position of c", "view of camera"
  std::vector<geometry::ConvexRegion> pieces_W;  // world frame, disjoint interiors
};

/// A `require settled` statement the attempt ran (docs/language.md): checked by
/// CheckSettledScene once a simulator has let the scene come to rest (--settle).
struct SettledRequirement {
  const CompiledProgram* program = nullptr;  // must outlive the scene, as its classes do
  int module = 0;
  const Expr* condition = nullptr;
  SourceSpan span;  // the statement
  /// The names the statement saw when it ran (a loop variable's value of that iteration).
  std::shared_ptr<const std::unordered_map<std::string, Value>> names;
};

struct Scene {
  std::vector<SceneObject> objects;
  std::vector<std::pair<std::string, Value>> params;
  /// The region the main module binds to `workspace` (null when none), e.g. for drawing.
  RegionPtr workspace;
  /// Filled only when RunOptions::record_regions is set.
  std::vector<PlacedRegion> regions;
  /// The attempt's `require settled` statements, in the order they ran.
  std::vector<SettledRequirement> settled_requirements;
  /// Set once a simulator has moved the free bodies to where they come to rest (--settle):
  /// the simulated seconds that took.
  std::optional<double> settled_s;
};

/// Why an attempt was rejected. Reasons are grouped by `kind` and `culprit` for accounting.
enum class RejectionKind {
  kCollision,      // two objects' boxes overlap
  kRequirement,    // a `require` failed
  kWorkspace,      // an object's box is not inside the workspace
  kEmptyRegion,    // the intersection of an object's position specifiers is empty
  kOutsideRegion,  // a point-valued position is not inside another specifier's region
  kRelativePosition,  // naive mode: a left of / ahead of / ... specifier does not hold
  kContainment,       // naive mode: an on / completely on / in specifier does not hold
  kOccluded,          // `visible from`: another object hides (part of) the object from the camera
  kVisible,           // `not visible from`: the camera sees the object's centre
  kUnstable,          // --stable: a free body moved or turned under gravity (sim/stability.h)
  kUnsettled,         // --settle: the scene at rest breaks a `require settled` or the workspace
};

struct Rejection {
  RejectionKind kind;
  std::string culprit;  // e.g. "tr_1 and tr_2", "require at scene.prs:12"
  SourceSpan span;      // the statement or specifier responsible
  std::string detail;   // numbers for the failure message
  /// The attempt drew no random value, so every attempt would be rejected the same way.
  bool certain = false;
};

/// A stable lowercase name for a rejection kind ("collision", "requirement", ...).
const char* RejectionKindName(RejectionKind kind);

}  // namespace prs::lang
