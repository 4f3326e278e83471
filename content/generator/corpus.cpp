#include "corpus.h"

#include "gltf_writer.h"
#include "sky_map.h"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace tl::content {
namespace {

// SplitMix64: the same draws on every platform and standard library (std's distributions are
// implementation-defined), so a seed names the same corpus everywhere.
class Draw {
 public:
  explicit Draw(uint64_t state) : state_(state) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float uniform() { return float(next() >> 40) * (1.0f / 16777216.0f); }  // [0, 1)
  float between(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  float logBetween(float lo, float hi) { return lo * std::pow(hi / lo, uniform()); }
  int integer(int lo, int hi) { return lo + int(next() % uint64_t(hi - lo + 1)); }  // inclusive
  bool chance(float p) { return uniform() < p; }
  template <class T>
  const T& pick(const std::vector<T>& options) {
    return options[size_t(next() % options.size())];
  }

 private:
  uint64_t state_;
};

// A rectangle in a wall's plane: [a0, a1] along its first in-plane axis, [b0, b1] along its second.
struct Rect {
  float a0, a1, b0, b1;
  bool empty() const { return a1 <= a0 || b1 <= b0; }
};

// `outer` less the holes, as disjoint rectangles: strips between the holes' a-edges, each cut
// where holes cover it; neighbouring strips with the same cut are merged (a wall with one door
// is three pieces).
std::vector<Rect> subtractHoles(const Rect& outer, const std::vector<Rect>& holes) {
  std::vector<Rect> clipped;
  for (const Rect& h : holes) {
    Rect c{std::max(h.a0, outer.a0), std::min(h.a1, outer.a1), std::max(h.b0, outer.b0), std::min(h.b1, outer.b1)};
    if (!c.empty()) clipped.push_back(c);
  }
  std::vector<float> cuts{outer.a0, outer.a1};
  for (const Rect& h : clipped) cuts.push_back(h.a0), cuts.push_back(h.a1);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<Rect> pieces;
  std::vector<Rect> previous;  // the last strip's pieces, to merge along a
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const float a0 = cuts[i], a1 = cuts[i + 1], mid = 0.5f * (a0 + a1);
    std::vector<std::pair<float, float>> covered;
    for (const Rect& h : clipped)
      if (h.a0 < mid && mid < h.a1) covered.push_back({h.b0, h.b1});
    std::sort(covered.begin(), covered.end());
    std::vector<Rect> strip;
    float b = outer.b0;
    for (auto [c0, c1] : covered) {
      if (c0 > b) strip.push_back({a0, a1, b, c0});
      b = std::max(b, c1);
    }
    if (b < outer.b1) strip.push_back({a0, a1, b, outer.b1});
    // Merge with the previous strip where the b-range is the same.
    for (Rect& r : strip) {
      auto same = std::find_if(previous.begin(), previous.end(),
                               [&](const Rect& p) { return p.b0 == r.b0 && p.b1 == r.b1 && p.a1 == r.a0; });
      if (same != previous.end()) {
        for (Rect& p : pieces)
          if (p.a0 == same->a0 && p.b0 == same->b0 && p.a1 == same->a1 && p.b1 == same->b1) p.a1 = r.a1, r.a0 = p.a0;
      } else {
        pieces.push_back(r);
      }
    }
    previous = strip;
  }
  return pieces;
}

// The planar face of a box side subdivided into cells of about `cell` (at most 64 a side).
void gridFace(Shape& s, glm::vec3 origin, glm::vec3 u, glm::vec3 v, float cell) {
  const int nu = std::clamp(int(std::ceil(glm::length(u) / cell)), 1, 64);
  const int nv = std::clamp(int(std::ceil(glm::length(v) / cell)), 1, 64);
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  const uint32_t base = uint32_t(s.positions.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const float fu = float(i) / float(nu), fv = float(j) / float(nv);
      s.positions.push_back(origin + u * fu + v * fv);
      s.normals.push_back(n);
      s.uvs.push_back({fu * glm::length(u), fv * glm::length(v)});
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const uint32_t a = base + uint32_t(j * (nu + 1) + i), b = a + 1, c = a + uint32_t(nu + 1), d = c + 1;
      for (uint32_t k : {a, b, d, a, d, c}) s.indices.push_back(k);
    }
}

// An axis-aligned box from lo to hi, its faces cut into cells of about `cell` (huge: 12 triangles).
Shape gridBox(glm::vec3 lo, glm::vec3 hi, float cell) {
  Shape s;
  const glm::vec3 X(hi.x - lo.x, 0, 0), Y(0, hi.y - lo.y, 0), Z(0, 0, hi.z - lo.z);
  gridFace(s, {lo.x, lo.y, hi.z}, X, Y, cell);   // +Z
  gridFace(s, {hi.x, lo.y, lo.z}, -X, Y, cell);  // -Z
  gridFace(s, {hi.x, lo.y, hi.z}, -Z, Y, cell);  // +X
  gridFace(s, {lo.x, lo.y, lo.z}, Z, Y, cell);   // -X
  gridFace(s, {lo.x, hi.y, hi.z}, X, -Z, cell);  // +Y
  gridFace(s, {lo.x, lo.y, lo.z}, X, Z, cell);   // -Y
  return s;
}

glm::vec3 hsv(float h, float s, float v) {
  const glm::vec3 k = glm::clamp(glm::abs(glm::mod(h * 6.0f + glm::vec3(0.0f, 4.0f, 2.0f), 6.0f) - 3.0f) - 1.0f, 0.0f, 1.0f);
  return v * glm::mix(glm::vec3(1.0f), k, s);
}

// One room: the inside box. Its six sides are walls of thickness t outside it (or quads on it).
struct Room {
  glm::vec3 lo, hi;
  // Holes per side, in that side's plane coordinates (Side order: -x, +x, -y, +y, -z, +z).
  std::array<std::vector<Rect>, 6> holes;
  glm::vec3 size() const { return hi - lo; }
};

// The two in-plane axes of a side whose normal is along `axis` (a, b as Rect uses them).
int axisA(int axis) { return axis == 0 ? 2 : 0; }
int axisB(int axis) { return axis == 1 ? 2 : 1; }

// Side s of a room: normal axis s / 2, at the low (even s) or high (odd s) end.
Rect sideRect(const Room& r, int side) {
  const int axis = side / 2, a = axisA(axis), b = axisB(axis);
  return {r.lo[a], r.hi[a], r.lo[b], r.hi[b]};
}

// What the generator knows about the scene as it builds it.
class InteriorBuilder {
 public:
  InteriorBuilder(SceneWriter& w, bool thick, float thickness, float cell)
      : w_(w), thick_(thick), t_(thickness), cell_(cell) {}

  // The room's six walls with their holes: boxes of thickness t outside the inside faces,
  // overlapping at the corners (no seam a ray could slip through), or one quad per piece.
  void walls(const Room& room, const std::string& name, int floorMat, int wallMat, int ceilingMat) {
    for (int side = 0; side < 6; ++side) {
      const int axis = side / 2, a = axisA(axis), b = axisB(axis);
      const bool high = side % 2 == 1;
      const int material = axis == 1 ? (high ? ceilingMat : floorMat) : wallMat;
      Rect outer = sideRect(room, side);
      // Boxes reach over the corners by the thickness: no seam is left for a ray to slip through.
      if (thick_) outer = {outer.a0 - t_, outer.a1 + t_, outer.b0 - t_, outer.b1 + t_};
      const float plane = high ? room.hi[axis] : room.lo[axis];
      std::vector<Rect> holes = room.holes[size_t(side)];
      // Quads: where a room built before has a side on the same plane (a wall two rooms share)
      // that side is the wall already; a second quad there would fight it.
      if (!thick_)
        for (const EmittedSide& e : emitted_)
          if (e.axis == axis && std::abs(e.plane - plane) <= 1e-6f * std::max(std::abs(plane), 1e-30f) + 1e-30f)
            holes.push_back(e.rect);
      if (!thick_) emitted_.push_back({axis, plane, outer});
      const std::vector<Rect> pieces = subtractHoles(outer, holes);
      for (size_t k = 0; k < pieces.size(); ++k) {
        const Rect& p = pieces[k];
        const std::string piece = fmt::format("{}_{}{}", name, kSideNames[side], pieces.size() > 1 ? fmt::format("_{}", k) : "");
        if (thick_) {
          glm::vec3 lo, hi;
          lo[axis] = high ? plane : plane - t_;
          hi[axis] = high ? plane + t_ : plane;
          lo[a] = p.a0, hi[a] = p.a1, lo[b] = p.b0, hi[b] = p.b1;
          add(piece, gridBox(lo, hi, cell_), material);
        } else {
          add(piece, quadFacingIn(axis, high, plane, p), material);
        }
      }
    }
  }

  // A box standing in a room (furniture, a lamp's body), tessellated like the walls.
  void block(const std::string& name, glm::vec3 lo, glm::vec3 hi, int material) {
    add(name, gridBox(lo, hi, thick_ ? cell_ : 1e30f), material);
  }
  void shape(const std::string& name, const Shape& s, int material) { add(name, s, material); }
  // Ground outside around the building, its top at `top`: a slab like the walls, or a quad.
  void ground(const std::string& name, const Rect& xz, float top, int material) {
    if (thick_) add(name, gridBox({xz.a0, top - t_, xz.b0}, {xz.a1, top, xz.b1}, cell_), material);
    else add(name, quadFacingIn(1, false, top, {xz.a0, xz.a1, xz.b0, xz.b1}), material);
  }

  uint32_t triangles() const { return triangles_; }

 private:
  static constexpr const char* kSideNames[6] = {"west", "east", "floor", "ceiling", "north", "south"};
  struct EmittedSide {
    int axis;
    float plane;
    Rect rect;
  };
  std::vector<EmittedSide> emitted_;  // quads: every side built so far

  // One quad on the side's plane whose normal points into the room.
  static Shape quadFacingIn(int axis, bool high, float plane, const Rect& p) {
    const int a = axisA(axis), b = axisB(axis);
    glm::vec3 origin(0.0f), u(0.0f), v(0.0f);
    origin[axis] = plane, origin[a] = p.a0, origin[b] = p.b0;
    u[a] = p.a1 - p.a0;
    v[b] = p.b1 - p.b0;
    // cross(u, v) points along +axis when (a, b, axis) is right-handed; flip to face inwards.
    const float along = glm::cross(u, v)[axis];
    const bool wantPositive = high ? false : true;
    Shape s;
    if ((along > 0.0f) == wantPositive) gridFace(s, origin, u, v, 1e30f);
    else gridFace(s, origin, v, u, 1e30f);
    return s;
  }

  void add(const std::string& name, const Shape& s, int material) {
    w_.node(name, w_.mesh(name, s, material), glm::vec3(0.0f));
    triangles_ += uint32_t(s.indices.size() / 3);
  }

  SceneWriter& w_;
  bool thick_;
  float t_, cell_;
  uint32_t triangles_ = 0;
};

// A door, windows, slits or a skylight in `room`'s sides; returns the inward normal of the
// wall light mainly enters through (zero for the roof) for aiming the sun.
glm::vec3 cutOpenings(Room& room, const std::string& kind, const std::vector<int>& exteriorSides, Draw& d) {
  const glm::vec3 size = room.size();
  auto wallHole = [&](int side, float widthShare, float heightShare, float sillShare) {
    const Rect r = sideRect(room, side);
    const float len = r.a1 - r.a0, h = size.y;
    const float width = std::min(widthShare * len, 0.9f * len);
    const float at = r.a0 + d.between(0.05f * len, 0.95f * len - width);
    const float bottom = room.lo.y + sillShare * h, top = std::min(bottom + heightShare * h, room.lo.y + 0.95f * h);
    room.holes[size_t(side)].push_back({at, at + width, bottom, top});
  };
  auto inward = [](int side) {
    glm::vec3 n(0.0f);
    n[side / 2] = side % 2 == 0 ? 1.0f : -1.0f;
    return n;
  };
  if (kind == "door") {
    const int side = d.pick(exteriorSides);
    wallHole(side, d.between(0.12f, 0.35f), d.between(0.55f, 0.85f), 0.0f);
    return inward(side);
  }
  if (kind == "windows") {
    const int side = d.pick(exteriorSides);
    const int count = d.integer(1, 4);
    for (int i = 0; i < count; ++i) {
      // Windows side by side along the wall, each in its own share of it.
      const Rect r = sideRect(room, side);
      const float len = r.a1 - r.a0, share = len / float(count);
      const float width = share * d.between(0.3f, 0.7f);
      const float at = r.a0 + share * float(i) + d.between(0.0f, share - width);
      const float bottom = room.lo.y + d.between(0.25f, 0.5f) * size.y;
      const float top = std::min(bottom + d.between(0.2f, 0.4f) * size.y, room.lo.y + 0.95f * size.y);
      room.holes[size_t(side)].push_back({at, at + width, bottom, top});
    }
    return inward(side);
  }
  // The roof (side 3: +y): a = x, b = z.
  const Rect roof = sideRect(room, 3);
  if (kind == "slits") {
    // Narrow strips across the room's shorter horizontal side, spread along its longer one.
    const bool alongX = size.x >= size.z;
    const int count = d.integer(2, 6);
    const float longLen = alongX ? size.x : size.z;
    for (int i = 0; i < count; ++i) {
      const float centre = (float(i) + 0.5f) / float(count) * longLen;
      const float width = d.between(0.01f, 0.03f) * longLen;
      if (alongX) room.holes[3].push_back({roof.a0 + centre - width / 2, roof.a0 + centre + width / 2, roof.b0 + 0.05f * size.z, roof.b1 - 0.05f * size.z});
      else room.holes[3].push_back({roof.a0 + 0.05f * size.x, roof.a1 - 0.05f * size.x, roof.b0 + centre - width / 2, roof.b0 + centre + width / 2});
    }
    return glm::vec3(0.0f);
  }
  if (kind == "skylight") {
    const float wx = d.between(0.15f, 0.35f) * size.x, wz = d.between(0.15f, 0.35f) * size.z;
    const float x = roof.a0 + d.between(0.1f * size.x, 0.9f * size.x - wx), z = roof.b0 + d.between(0.1f * size.z, 0.9f * size.z - wz);
    room.holes[3].push_back({x, x + wx, z, z + wz});
    return glm::vec3(0.0f);
  }
  return glm::vec3(0.0f);
}

// A passage between two rooms that touch along x (a's +x side faces b's -x side): the same
// hole in both walls, over the z and y range they share.
void joinAlongX(Room& a, Room& b, Draw& d, bool wide) {
  const float z0 = std::max(a.lo.z, b.lo.z), z1 = std::min(a.hi.z, b.hi.z);
  const float h = std::min(a.size().y, b.size().y);
  const float shared = z1 - z0;
  float width = wide ? 0.9f * shared : std::min(d.between(0.15f, 0.4f) * shared, 0.9f * shared);
  const float at = wide ? z0 + 0.05f * shared : z0 + d.between(0.05f * shared, 0.95f * shared - width);
  const Rect hole{at, at + width, a.lo.y, a.lo.y + (wide ? 0.9f : d.between(0.6f, 0.85f)) * h};
  a.holes[1].push_back(hole);
  b.holes[0].push_back(hole);
}
// The same along z (a's +z side faces b's -z side); a = x in those sides' planes.
void joinAlongZ(Room& a, Room& b, Draw& d, bool wide) {
  const float x0 = std::max(a.lo.x, b.lo.x), x1 = std::min(a.hi.x, b.hi.x);
  const float h = std::min(a.size().y, b.size().y);
  const float shared = x1 - x0;
  float width = wide ? 0.9f * shared : std::min(d.between(0.15f, 0.4f) * shared, 0.9f * shared);
  const float at = wide ? x0 + 0.05f * shared : x0 + d.between(0.05f * shared, 0.95f * shared - width);
  const Rect hole{at, at + width, a.lo.y, a.lo.y + (wide ? 0.9f : d.between(0.6f, 0.85f)) * h};
  a.holes[5].push_back(hole);
  b.holes[4].push_back(hole);
}

tinygltf::Value text(const std::string& s) { return tinygltf::Value(s); }

CorpusScene writeInterior(const std::filesystem::path& dir, uint64_t seed, uint32_t index) {
  Draw d(seed * 0x9E3779B97F4A7C15ull + uint64_t(index) * 0xD1B54A32D192ED03ull + 1u);
  d.next();
  CorpusScene info;
  info.name = fmt::format("interior_{:03d}", index);
  info.size = d.logBetween(0.5f, 500.0f);
  info.shape = d.pick(std::vector<std::string>{"box", "hall", "corridor", "l_shape", "suite"});
  info.walls = d.chance(0.5f) ? "thick" : "quads";
  info.albedo = d.pick(std::vector<std::string>{"white", "grey", "saturated"});
  const bool thick = info.walls == "thick";
  const float u = info.size;

  // The rooms, in metres relative to u. Room 0 holds camera 0; light enters through the
  // room `entry`.
  std::vector<Room> rooms;
  auto room = [&](glm::vec3 lo, glm::vec3 size) { rooms.push_back(Room{lo, lo + size, {}}); };
  if (info.shape == "box") {
    const float depth = u * d.between(0.55f, 1.0f);
    room({0, 0, 0}, {u, std::min(u, depth) * d.between(0.45f, 0.9f), depth});
  } else if (info.shape == "hall") {
    const float width = u * d.between(0.18f, 0.35f);
    room({0, 0, 0}, {u, width * d.between(0.6f, 1.3f), width});
  } else if (info.shape == "corridor") {
    const float width = u * d.between(0.04f, 0.09f);
    room({0, 0, 0}, {u, width * d.between(1.1f, 1.6f), width});
  }
  // The gap between two rooms' inside faces: both walls' thickness; quads rooms share one
  // quad on the plane they meet (InteriorBuilder::walls).
  const float minSide = 0.25f * u;  // the smallest inside dimension a room of this draw has, about
  const float t = thick ? d.between(0.03f, 0.08f) * minSide : 0.0f;
  const float gap = thick ? 2.0f * t : 0.0f;
  const float touching = 1e-5f * u;  // two sides closer than this lie on one plane
  if (info.shape == "l_shape") {
    const float wa = u * d.between(0.25f, 0.45f), ha = wa * d.between(0.6f, 1.2f);
    room({0, 0, 0}, {u, ha, wa});
    const float wb = u * d.between(0.25f, 0.45f), lb = u * d.between(0.5f, 0.9f);
    room({u - wb, 0, wa + gap}, {wb, ha * d.between(0.8f, 1.2f), lb});
    joinAlongZ(rooms[0], rooms[1], d, true);
  } else if (info.shape == "suite") {
    const int count = d.integer(2, 3);
    const float depth = u * d.between(0.3f, 0.6f);
    float x = 0.0f;
    for (int i = 0; i < count; ++i) {
      const float width = u * d.between(0.3f, 0.6f);
      room({x, 0, 0}, {width, depth * d.between(0.5f, 0.9f), depth * d.between(0.8f, 1.0f)});
      x += width + gap;
    }
    for (int i = 0; i + 1 < count; ++i) joinAlongX(rooms[size_t(i)], rooms[size_t(i) + 1], d, false);
  }

  // A sealed room beside room 0, west of it (no other room is there), with its own camera. Only
  // with walls of some thickness: sunlight slips past a shadow map's texels where two sides of
  // no thickness meet at a corner (the shadow-mapped paths' stated limit, docs/accuracy.md),
  // which would say nothing about light leaking through walls.
  info.sealedRoom = thick && d.chance(0.5f);
  Room sealed{};
  if (info.sealedRoom) {
    const Room& r0 = rooms[0];
    const glm::vec3 s = r0.size() * glm::vec3(d.between(0.5f, 1.0f), 1.0f, d.between(0.6f, 1.0f));
    sealed = Room{{r0.lo.x - gap - s.x, r0.lo.y, r0.lo.z}, {r0.lo.x - gap, r0.lo.y + s.y, r0.lo.z + s.z}, {}};
  }

  // Openings: in the room light enters (the last room of a suite half the time, else room 0),
  // in its sides that no other room (nor the sealed one) touches.
  info.openings = d.pick(std::vector<std::string>{"none", "door", "windows", "slits", "skylight"});
  const size_t entry = info.shape == "suite" && d.chance(0.5f) ? rooms.size() - 1 : 0;
  std::vector<const Room*> neighbours;
  for (size_t r = 0; r < rooms.size(); ++r)
    if (r != entry) neighbours.push_back(&rooms[r]);
  if (info.sealedRoom) neighbours.push_back(&sealed);
  std::vector<int> exterior;
  for (int side : {0, 1, 4, 5}) {
    const Room& a = rooms[entry];
    const int axis = side / 2, other = 2 - axis;  // the side's normal axis and its horizontal in-plane axis
    const float plane = side % 2 == 0 ? a.lo[axis] : a.hi[axis];
    bool touches = false;
    for (const Room* b : neighbours) {
      const float facing = side % 2 == 0 ? b->hi[axis] : b->lo[axis];
      const bool overlaps = b->lo[other] < a.hi[other] && a.lo[other] < b->hi[other];
      if (overlaps && std::abs(plane - facing) <= gap + touching) touches = true;
    }
    if (!touches) exterior.push_back(side);
  }
  const glm::vec3 entryNormal = cutOpenings(rooms[entry], info.openings, exterior, d);

  SceneWriter w(info.name);
  const float tessellation = thick ? std::max(0.06f * std::min({rooms[0].size().x, rooms[0].size().y, rooms[0].size().z}),
                                              1e-6f)
                                   : 1e30f;
  InteriorBuilder build(w, thick, t, tessellation);

  // Materials (Lambertian: roughness 1, dielectric; compared with --materials diffuse).
  auto colour = [&]() -> glm::vec3 {
    if (info.albedo == "white") return glm::vec3(0.9f);
    if (info.albedo == "grey") return glm::vec3(d.between(0.15f, 0.85f));
    return hsv(d.uniform(), d.between(0.6f, 1.0f), d.between(0.35f, 0.9f));
  };
  MaterialSpec wallSpec{"walls", colour(), 0.0f, 1.0f};
  MaterialSpec floorSpec{"floor", colour(), 0.0f, 1.0f};
  MaterialSpec ceilingSpec{"ceiling", colour(), 0.0f, 1.0f};
  MaterialSpec furnitureSpec{"furniture", colour(), 0.0f, 1.0f};
  for (MaterialSpec* m : {&wallSpec, &floorSpec, &ceilingSpec, &furnitureSpec}) m->doubleSided = true;
  const int wallMat = w.material(wallSpec), floorMat = w.material(floorSpec), ceilingMat = w.material(ceilingSpec);
  const int furnitureMat = w.material(furnitureSpec);

  for (size_t r = 0; r < rooms.size(); ++r) build.walls(rooms[r], fmt::format("room{}", r), floorMat, wallMat, ceilingMat);
  if (info.sealedRoom) build.walls(sealed, "sealed", floorMat, wallMat, ceilingMat);

  // Camera 0 in room 0, away from its walls, looking across it.
  const Room& r0 = rooms[0];
  const glm::vec3 s0 = r0.size();
  const glm::vec3 eye = r0.lo + s0 * glm::vec3(d.between(0.2f, 0.8f), d.between(0.3f, 0.6f), d.between(0.2f, 0.8f));
  glm::vec3 target = r0.lo + s0 * glm::vec3(d.uniform(), d.between(0.15f, 0.8f), d.uniform());
  if (info.shape == "corridor" || info.shape == "hall") target.x = eye.x < r0.lo.x + 0.5f * s0.x ? r0.hi.x : r0.lo.x;
  if (glm::length(target - eye) < 0.2f * glm::length(s0)) target = r0.lo + s0 * glm::vec3(1.0f - (eye - r0.lo) / s0);
  const float smallest = std::min({s0.x, s0.y, s0.z});

  // Furniture: boxes on room 0's floor, clear of the camera.
  const int blocks = d.integer(0, 4);
  for (int i = 0; i < blocks; ++i) {
    const glm::vec3 size = s0 * glm::vec3(d.between(0.05f, 0.25f), d.between(0.1f, 0.5f), d.between(0.05f, 0.25f));
    const glm::vec3 lo = r0.lo + glm::vec3(d.between(0.05f, 0.95f) * s0.x - size.x / 2, 0.0f, d.between(0.05f, 0.95f) * s0.z - size.z / 2);
    const glm::vec3 hi = lo + size;
    const glm::vec3 near = glm::clamp(eye, lo, hi);
    if (glm::length(near - eye) < 0.1f * smallest + 0.02f * glm::length(s0)) continue;
    build.block(fmt::format("block_{}", i), glm::max(lo, r0.lo), glm::min(hi, r0.hi), furnitureMat);
  }

  // Light. Through openings: the sun (aimed through the opening half the time) and the sky;
  // closed interiors, and some open ones, also have lamps, panels or an emissive mesh.
  std::vector<std::string> lights;
  const bool open = info.openings != "none";
  // A fifth of the open interiors are lit by an HDRI alone (a sky with a sun disc in its
  // texels, turned to a random azimuth), set up in the scene's lighting sidecar, as an artist's
  // export lit by an environment map would be; their other lights are meshes (a sidecar's
  // light list is the scene's whole).
  const bool hdri = open && d.chance(0.2f);
  if (hdri) {
    w.sky(glm::vec3(0.0f));
    const std::filesystem::path sky = dir / "environments" / "corpus_sky.exr";
    if (!std::filesystem::exists(sky)) writeCourtyardSky(sky);
    const std::string sidecar = fmt::format(R"({{
  "format": "twinlight.lighting",
  "version": 1,
  "sun": {{"direction": [0.3, -1, 0.2], "irradiance": 0}},
  "sky": {{"radiance": 0}},
  "exposure_ev": null,
  "environment": {{"file": "environments/corpus_sky.exr", "rotation_deg": {:.1f}, "intensity": {:.3f}}},
  "lights": []
}}
)", d.between(0.0f, 360.0f), d.between(0.5f, 2.0f));
    writeLightingSidecar(dir / (info.name + ".lighting.json"), sidecar.c_str());
    lights.push_back("hdri");
  }
  if (open && !hdri) {
    // The sun shines in through the opening (aimed at a wall opening, or high over a roof
    // opening) or comes from anywhere; a sun that may miss the openings comes with a sky, so
    // no open interior is left without light.
    const bool sun = d.chance(0.75f);
    const bool wallOpening = glm::length(entryNormal) > 0.0f;
    const bool aimed = sun && (!wallOpening || d.chance(0.7f));
    const bool sky = !aimed || d.chance(0.6f);
    if (sun) {
      float elevation;
      glm::vec3 horizontal;
      if (aimed && wallOpening) {
        const float turn = glm::radians(d.between(-35.0f, 35.0f));
        horizontal = glm::vec3(entryNormal.x * std::cos(turn) - entryNormal.z * std::sin(turn), 0.0f,
                               entryNormal.x * std::sin(turn) + entryNormal.z * std::cos(turn));
        elevation = glm::radians(d.between(12.0f, 45.0f));
      } else {
        const float azimuth = d.between(0.0f, glm::two_pi<float>());
        horizontal = glm::vec3(std::cos(azimuth), 0.0f, std::sin(azimuth));
        elevation = glm::radians(aimed ? d.between(45.0f, 85.0f) : d.between(10.0f, 80.0f));
      }
      const glm::vec3 travel = std::cos(elevation) * horizontal - glm::vec3(0.0f, std::sin(elevation), 0.0f);
      w.sun(travel, d.between(5.0f, 30.0f), glm::mix(glm::vec3(1.0f), glm::vec3(1.0f, 0.9f, 0.75f), d.uniform()));
      lights.push_back("sun");
    }
    const glm::vec3 tints[3] = {{0.6f, 0.75f, 1.0f}, {1.0f, 1.0f, 1.0f}, {1.0f, 0.9f, 0.8f}};
    w.sky(sky ? tints[d.integer(0, 2)] * d.between(0.1f, 1.5f) : glm::vec3(0.0f));
    if (sky) lights.push_back("sky");
    // Ground outside, so light also bounces in off it.
    if (d.chance(0.6f)) {
      glm::vec3 lo(1e30f), hi(-1e30f);
      for (const Room& r : rooms) lo = glm::min(lo, r.lo), hi = glm::max(hi, r.hi);
      if (info.sealedRoom) lo = glm::min(lo, sealed.lo);
      const float margin = 2.0f * std::max(hi.x - lo.x, hi.z - lo.z);
      // The ground's top at the floor's level, with the building's footprint (walls included) cut out.
      const Rect footprint{lo.x - t, hi.x + t, lo.z - t, hi.z + t};
      MaterialSpec groundSpec{"ground", glm::vec3(d.between(0.2f, 0.5f)), 0.0f, 1.0f};
      groundSpec.doubleSided = true;
      const int groundMat = w.material(groundSpec);
      const std::vector<Rect> pieces = subtractHoles({lo.x - margin, hi.x + margin, lo.z - margin, hi.z + margin}, {footprint});
      for (size_t k = 0; k < pieces.size(); ++k) build.ground(fmt::format("ground_{}", k), pieces[k], lo.y, groundMat);
    }
  } else if (!open) {
    w.sky(glm::vec3(0.0f));
  }
  if (!open || d.chance(0.3f)) {
    const std::vector<std::string> kinds = hdri ? std::vector<std::string>{"panels", "emitter"}
                                                : std::vector<std::string>{"panels", "emitter", "lamps", "spots"};
    const int count = d.integer(1, 2);
    for (int k = 0; k < count; ++k) {
      const std::string kind = d.pick(kinds);
      if (std::find(lights.begin(), lights.end(), kind) != lights.end()) continue;
      lights.push_back(kind);
      // Irradiance aimed at on the floor below the light (Twinlight's scale), so every size of
      // room is about as bright: the light's power grows with the square of the room.
      const size_t lit = size_t(d.integer(0, int(rooms.size()) - 1));
      const Room& r = rooms[lit];
      const glm::vec3 rs = r.size();
      const float target = d.between(0.5f, 5.0f);
      if (kind == "panels") {
        const int panels = d.integer(1, 4);
        for (int i = 0; i < panels; ++i) {
          const glm::vec3 size = rs * glm::vec3(d.between(0.06f, 0.2f), 0.01f, d.between(0.06f, 0.2f));
          const glm::vec3 centre = r.lo + rs * glm::vec3(d.between(0.15f, 0.85f), 0.97f, d.between(0.15f, 0.85f));
          const float area = size.x * size.z, drop = 0.97f * rs.y;
          const float radiance = std::min(target * drop * drop / area, 1e6f);
          MaterialSpec spec{fmt::format("panel_{}", i), glm::vec3(0.8f), 0.0f, 1.0f, glm::vec3(1.0f, 0.95f, 0.85f), radiance};
          spec.doubleSided = true;
          build.block(fmt::format("panel_{}", i), centre - size / 2.0f, centre + size / 2.0f, w.material(spec));
        }
      } else if (kind == "emitter") {
        const float radius = d.between(0.02f, 0.08f) * std::min({rs.x, rs.y, rs.z});
        const glm::vec3 centre = r.lo + rs * glm::vec3(d.between(0.2f, 0.8f), d.between(0.2f, 0.7f), d.between(0.2f, 0.8f));
        const float reach = 0.5f * rs.y;
        const float radiance = std::min(target * reach * reach / (glm::pi<float>() * radius * radius), 1e6f);
        MaterialSpec spec{"emitter", glm::vec3(0.8f), 0.0f, 1.0f, hsv(d.uniform(), d.between(0.0f, 0.5f), 1.0f), radiance};
        build.shape("emitter", transformed(sphere(radius, 24, 12), glm::translate(glm::mat4(1.0f), centre)), w.material(spec));
      } else {
        const int lamps = d.integer(1, 3);
        for (int i = 0; i < lamps; ++i) {
          const glm::vec3 at = r.lo + rs * glm::vec3(d.between(0.15f, 0.85f), d.between(0.5f, 0.9f), d.between(0.15f, 0.85f));
          const float drop = at.y - r.lo.y;
          const float candela = 683.0f * target * drop * drop;  // I = E d^2 on Twinlight's scale, in cd
          const glm::vec3 tint = glm::mix(glm::vec3(1.0f), glm::vec3(1.0f, 0.8f, 0.6f), d.uniform());
          if (kind == "lamps") {
            w.pointLight(fmt::format("lamp_{}", i), at, candela, tint);
          } else {
            const float inner = d.between(15.0f, 35.0f);
            const glm::vec3 aim = glm::normalize(glm::vec3(d.between(-0.4f, 0.4f), -1.0f, d.between(-0.4f, 0.4f)));
            w.spotLight(fmt::format("spot_{}", i), at, aim, 3.0f * candela, inner, inner + d.between(5.0f, 20.0f), tint);
          }
        }
      }
    }
  }
  info.lights.clear();
  for (size_t i = 0; i < lights.size(); ++i) info.lights += (i ? "+" : "") + lights[i];

  const double znear = 0.01 * double(smallest);
  const float fov = d.between(55.0f, 75.0f);
  w.camera("inside", eye, target, fov, znear);
  if (info.sealedRoom) {
    const glm::vec3 ss = sealed.size();
    const glm::vec3 from = sealed.lo + ss * glm::vec3(0.3f, 0.5f, 0.5f);
    w.camera("sealed_room", from, glm::vec3(sealed.hi.x, sealed.lo.y + 0.4f * ss.y, sealed.lo.z + 0.5f * ss.z), fov,
             0.01f * std::min({ss.x, ss.y, ss.z}));
  }
  info.triangles = build.triangles();

  tinygltf::Value::Object extra;
  extra["seed"] = tinygltf::Value(double(seed));
  extra["index"] = tinygltf::Value(int(index));
  extra["size_m"] = tinygltf::Value(double(info.size));
  extra["shape"] = text(info.shape);
  extra["openings"] = text(info.openings);
  extra["lights"] = text(info.lights);
  extra["albedo"] = text(info.albedo);
  extra["walls"] = text(info.walls);
  extra["triangles"] = tinygltf::Value(int(info.triangles));
  extra["sealed_room"] = tinygltf::Value(info.sealedRoom);
  w.twinlightExtra("corpus", tinygltf::Value(extra));
  w.write(dir);
  return info;
}

}  // namespace

std::vector<CorpusScene> writeCorpus(const std::filesystem::path& dir, uint64_t seed, uint32_t first, uint32_t count) {
  std::filesystem::create_directories(dir);
  std::vector<CorpusScene> scenes;
  for (uint32_t i = first; i < first + count; ++i) scenes.push_back(writeInterior(dir, seed, i));
  return scenes;
}

}  // namespace tl::content
