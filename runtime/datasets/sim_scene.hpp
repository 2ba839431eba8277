// The synthetic world the LiDAR simulator ray-casts: a ground plane plus analytic primitives
// (yawed boxes, vertical cylinders, axis-aligned ellipsoids) in a uniform 2-D grid over x–y for
// fast traversal, and a small list of moving primitives tested brute force. Exact intersections.
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace sgnlf::sim {

using V3 = Eigen::Vector3f;

// Surface classes: reflectance is per primitive; glass returns specularly (often dropped).
enum class Material : uint8_t { asphalt, paint, concrete, brick, plaster, glass, car_paint,
                                car_glass, metal, bark, foliage, stone, plastic };

struct Primitive {
  enum Type : uint8_t { box, cylinder, ellipsoid } type = box;
  Material material = Material::concrete;
  V3 center = V3::Zero();  // box/ellipsoid centre; cylinder: axis point at mid height
  V3 half = V3::Ones();    // box half extents (local x, y, z); cylinder (r, r, half height);
                           // ellipsoid radii
  float cos_yaw = 1.f, sin_yaw = 0.f;  // box rotation about z (local x → world)
  float reflectance = 0.3f;
  bool windows = false;  // facade with a grid of glass windows on its vertical faces
  uint16_t label = 0;    // 0 static (or an unlabelled mover); k > 0: moving actor k (sim_actors.hpp)

  static Primitive make_box(V3 c, V3 half, float yaw, Material m, float refl);
  static Primitive make_cylinder(float x, float y, float z0, float z1, float r, Material m, float refl);
  static Primitive make_ellipsoid(V3 c, V3 radii, Material m, float refl);
  // Conservative x–y bounds and max z.
  void bounds(float& x0, float& y0, float& x1, float& y1) const;
  float top() const { return center.z() + half.z(); }
};

struct Hit {
  float t = 0.f;
  V3 normal = V3::UnitZ();
  float reflectance = 0.f;
  Material material = Material::asphalt;
  uint16_t label = 0;  // the hit primitive's label (the ground: 0)
};

// Ray (origin o, unit direction d) against one primitive; true and `h` for the nearest t in
// (t_min, h.t). Origins inside a primitive see no hit from it.
bool intersect(const Primitive& p, const V3& o, const V3& d, float t_min, Hit& h);

class Scene {
 public:
  float ground_z = 0.f;
  float ground_reflectance = 0.12f;  // asphalt
  float ground_texture = 0.25f;      // relative patchiness of the ground reflectance
  uint64_t texture_seed = 0;

  void add(const Primitive& p) { prims_.push_back(p); built_ = false; }
  const std::vector<Primitive>& primitives() const { return prims_; }
  // Moving objects for the current frame (replaced per frame, tested brute force).
  std::vector<Primitive> dynamic;

  void build(float cell_m = 2.0f);
  // Nearest hit along the ray within (0, t_max); false when nothing is hit.
  bool cast(const V3& o, const V3& d, float t_max, Hit& h) const;

 private:
  bool cast_static(const V3& o, const V3& d, float t_max, Hit& h) const;
  std::vector<Primitive> prims_;
  bool built_ = false;
  float cell_ = 2.f, x0_ = 0.f, y0_ = 0.f;
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> cell_start_, cell_items_;
  std::vector<float> cell_top_;
};

}  // namespace sgnlf::sim
