// The export rules (docs/export.md): names, shape from `shape_type`, colour from `color`, a free
// body when `mass` is a positive number, inertia of a solid box or cylinder, contacts unless
// `allowCollisions`.
#include "export/body_rules.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace prs::exporting::internal {
namespace {

const lang::Value* Find(const Properties& properties, const std::string& name) {
  for (const auto& [key, value] : properties) {
    if (key == name) return &value;
  }
  return nullptr;
}

std::string Lowercase(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool NearlyEqual(double x, double y) { return std::fabs(x - y) <= 1e-9 * std::max(x, y); }

// A built-in shape is written natively when the formats have it: round across (width =
// length), and for a sphere as tall as wide, for a capsule at least as tall (round caps).
// Otherwise (an elliptic cylinder, an ellipsoid, a squat capsule) as its polytope.
Shape ClassifyPrimitive(shapes::Primitive kind, const Eigen::Vector3d& size) {
  const bool round = NearlyEqual(size.x(), size.y());
  switch (kind) {
    case shapes::Primitive::kCylinder: return round ? Shape::kCylinder : Shape::kMesh;
    case shapes::Primitive::kSphere: return round && NearlyEqual(size.x(), size.z()) ? Shape::kSphere : Shape::kMesh;
    case shapes::Primitive::kCapsule: return round && size.z() >= size.x() ? Shape::kCapsule : Shape::kMesh;
  }
  return Shape::kMesh;
}

Shape ReadShape(const ObjectFacts& facts, const std::string& label,
                std::vector<std::string>& warnings) {
  if (facts.dimensions.minCoeff() <= 0) return Shape::kNone;
  if (const lang::Value* shape = Find(facts.properties, "shape"); shape && shape->Is<lang::MeshRef>()) {
    return Shape::kMesh;
  }
  if (const lang::Value* shape = Find(facts.properties, "shape"); shape && shape->Is<lang::PrimitiveRef>()) {
    return ClassifyPrimitive(shape->As<lang::PrimitiveRef>().kind, facts.dimensions);
  }
  const lang::Value* value = Find(facts.properties, "shape_type");
  if (value == nullptr) return Shape::kBox;
  if (value->Is<lang::StringPtr>()) {
    const std::string shape = Lowercase(*value->As<lang::StringPtr>());
    if (shape == "cylinder") return Shape::kCylinder;
    if (shape == "box" || shape == "cube" || shape == "cuboid") return Shape::kBox;
  }
  warnings.push_back(
      fmt::format("{}: shape_type {} is not \"box\" or \"cylinder\"; exported as a box", label,
                  lang::Repr(*value)));
  return Shape::kBox;
}

Rgba ReadColor(const ObjectFacts& facts, const std::string& label,
               std::vector<std::string>& warnings) {
  const lang::Value* value = Find(facts.properties, "color");
  if (value == nullptr) return Rgba{};
  if (auto color = ParseColor(*value)) return *color;
  warnings.push_back(
      fmt::format("{}: color {} is not a colour name, a grey level or an RGB triple; exported grey",
                  label, lang::Repr(*value)));
  return Rgba{};
}

// A positive number makes a free body; 0 or no `mass` a static one.
double ReadMass(const ObjectFacts& facts, Shape shape, const std::string& label,
                std::vector<std::string>& warnings) {
  const lang::Value* value = Find(facts.properties, "mass");
  if (value == nullptr) return 0;
  if (!value->Is<double>() || value->As<double>() < 0) {
    warnings.push_back(fmt::format("{}: mass {} is not a number >= 0 (kg); exported static", label,
                                   lang::Repr(*value)));
    return 0;
  }
  if (shape == Shape::kNone && value->As<double>() > 0) {
    warnings.push_back(
        fmt::format("{}: a point has no volume to carry its mass; exported static", label));
    return 0;
  }
  return value->As<double>();
}

// A camera's vertical field of view, the value `in view of` uses (camera/camera.h): the
// simulator's camera must see what the sampler was told it sees.
double ReadFovy(const ObjectFacts& facts, const std::string& label, std::vector<std::string>& warnings) {
  const lang::Value* value = Find(facts.properties, "fovy_deg");
  if (value == nullptr) return 45;
  if (!value->Is<double>() || !(value->As<double>() > 0 && value->As<double>() < 180)) {
    warnings.push_back(fmt::format("{}: fovy_deg {} is not a number of degrees between 0 and 180; "
                                   "exported as 45", label, lang::Repr(*value)));
    return 45;
  }
  return value->As<double>();
}

}  // namespace

// Principal moments of a solid box, cylinder, sphere or capsule about its centre, in its own
// axes (a mesh: its box's).
Eigen::Vector3d CalcInertiaDiag(Shape shape, const Eigen::Vector3d& size, double mass_kg) {
  const double w = size.x(), l = size.y(), h = size.z();
  if (shape == Shape::kCylinder) {
    const double r = std::min(w, l) / 2;
    const double across = mass_kg * (3 * r * r + h * h) / 12;
    return {across, across, mass_kg * r * r / 2};
  }
  if (shape == Shape::kSphere) return Eigen::Vector3d::Constant(mass_kg * w * w / 10);  // 2/5 m r²
  if (shape == Shape::kCapsule) {
    // A cylinder of length s between two half balls, mass shared by volume; each half ball's
    // centroid is 3r/8 from the flat face (parallel axes).
    const double r = w / 2, s = h - w;
    const double v_cylinder = s, v_ball = 4.0 / 3 * r;  // both over π r²
    const double m_c = mass_kg * v_cylinder / (v_cylinder + v_ball), m_b = mass_kg - m_c;
    const double axial = m_c * r * r / 2 + m_b * 2 * r * r / 5;
    const double across = m_c * (3 * r * r + s * s) / 12 +
                          m_b * (2 * r * r / 5 + s * s / 4 + 3 * s * r / 8);
    return {across, across, axial};
  }
  return {mass_kg * (l * l + h * h) / 12, mass_kg * (w * w + h * h) / 12,
          mass_kg * (w * w + l * l) / 12};
}

std::string NameTable::MakeUnique(const std::string& wanted) {
  std::string base;
  for (const char c : wanted) base += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (base.empty() || std::isdigit(static_cast<unsigned char>(base[0]))) base = "_" + base;
  std::string name = base;
  for (int n = 2; taken_.count(name) > 0; ++n) name = base + "_" + std::to_string(n);
  taken_.insert(name);
  return name;
}

Body MakeBody(const ObjectFacts& facts, NameTable& names, std::vector<std::string>& warnings) {
  Body body;
  body.name = names.MakeUnique(
      facts.name.empty() ? facts.class_name + "_" + std::to_string(facts.index) : facts.name);
  const std::string label = fmt::format("object {} ({})", body.name, facts.class_name);
  body.class_name = facts.class_name;
  body.p_WO = facts.p_WO;
  body.R_WO = facts.R_WO.normalized();
  body.size = facts.dimensions;
  body.shape = ReadShape(facts, label, warnings);
  if (const lang::Value* shape = Find(facts.properties, "shape");
      shape && shape->Is<lang::PrimitiveRef>() && body.shape != Shape::kNone) {
    body.primitive = shape->As<lang::PrimitiveRef>().kind;
    body.mesh = shapes::MakePrimitiveShape(*body.primitive, body.size);
  } else if (body.shape == Shape::kMesh) {
    const auto& mesh = Find(facts.properties, "shape")->As<lang::MeshRef>();
    body.mesh = mesh.mesh;
    body.mesh_scale = mesh.scale;
  }
  body.color = ReadColor(facts, label, warnings);
  body.mass_kg = ReadMass(facts, body.shape, label, warnings);
  body.inertia_diag = CalcInertiaDiag(body.shape, body.size, body.mass_kg);
  body.collides = !facts.allow_collisions && body.shape != Shape::kNone;
  if (body.is_free() && !body.collides) {
    warnings.push_back(fmt::format(
        "{}: a mass and allowCollisions: True make a free body without contacts, which falls "
        "through whatever holds it up in a simulator (--stable and --settle refuse it)",
        label));
  }
  body.fovy_deg = ReadFovy(facts, label, warnings);
  return body;
}

}  // namespace prs::exporting::internal

namespace prs::exporting {

double CalcVolume(const Body& body) {
  const double w = body.size.x(), l = body.size.y(), h = body.size.z();
  switch (body.shape) {
    case Shape::kNone: return 0;
    case Shape::kCylinder: return M_PI * std::pow(body.cylinder_radius(), 2) * h;
    case Shape::kSphere: return 4.0 / 3 * M_PI * std::pow(w / 2, 3);
    case Shape::kCapsule: {
      const double r = w / 2;
      return M_PI * r * r * (h - w) + 4.0 / 3 * M_PI * r * r * r;
    }
    case Shape::kBox:
    case Shape::kMesh: return w * l * h;
  }
  return w * l * h;
}

void SetMass(Body& body, double mass_kg) {
  if (!(mass_kg > 0 && std::isfinite(mass_kg))) {
    throw std::invalid_argument(fmt::format("SetMass: mass {} kg of {} is not a positive number",
                                            mass_kg, body.name));
  }
  if (body.shape == Shape::kNone) {
    throw std::invalid_argument("SetMass: " + body.name + " is a point and has no volume");
  }
  body.mass_kg = mass_kg;
  body.inertia_diag = internal::CalcInertiaDiag(body.shape, body.size, mass_kg);
}

}  // namespace prs::exporting
