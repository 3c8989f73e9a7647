/// \file
/// The contact manifold of two boxes from their separating axis (\thesis{§3.2}: "the
/// intersection of two oriented rectangles in 2D").
///
/// Face contact: the reference face is the face of the box whose axis was chosen, facing the
/// other box; the incident face is the other box's face most anti-parallel to it. Clipping the
/// incident quad to the four side planes of the reference face (Sutherland-Hodgman) leaves at
/// most 8 points; those below the reference face (depth > -margin) are kept, moved midway
/// between the two surfaces, and, if more than 4, reduced to the 4 that keep the deepest point
/// and the largest area. Edge-edge contact: one point midway between the closest points of the
/// two support edges.
///
/// Box features, with corner k as in Obb::corner (bit i of k set: + along axis i):
/// \verbatim
///            2 +-----------+ 3
///             /|          /|              axis 1 (y)
///            / |         / |               |
///         6 +-----------+ 7|               +--- axis 0 (x)
///           |  |        |  |              /
///           |0 +--------|--+ 1          axis 2 (z), towards the viewer
///           | /         | /
///           |/          |/
///         4 +-----------+ 5
///
///   face f = 2*axis + (outward normal along +axis ? 1 : 0):  0 -x, 1 +x, 2 -y, 3 +y, 4 -z, 5 +z
///   edge e = 4*d + s1 + 2*s2 for an edge along axis d, where s1 (s2) is 1 when the edge lies
///            on the + side of axis (d+1)%3 ((d+2)%3).  e.g. edge 3 = corners 6-7, edge 4 = 0-2
///
///   A face seen from outside, axis m, u = axis (m+1)%3, v = axis (m+2)%3 (s = side of m):
///
///            v
///            ^      vertex k = centre + s h_m a_m + (+-h_u a_u) + (+-h_v a_v)
///     1 +----0----+ 0      0: (+u,+v)  1: (-u,+v)  2: (-u,-v)  3: (+u,-v)
///       |         |     edge k runs from vertex k to vertex k+1 (mod 4)
///       1         3  --> u
///       |         |     side plane k of a reference face is the plane through its edge k,
///     2 +----2----+ 3   perpendicular to the face
/// \endverbatim
///
/// Feature id of a face-contact point (same features, same id):
///   bits 0-2 and 3-5: the two lines the point lies on, in polygon order: 0..3 incident edge k,
///   4..7 reference side plane k-4 (an unclipped incident vertex k is (k-1, k));
///   bits 6-8 incident face; bits 9-11 reference face; bit 12 reference box (0 A, 1 B);
///   bits 13-14 contact kind, 0. Edge-edge point: bits 0-3 edge of A, 4-7 edge of B,
///   bits 13-14 = 1.
#include "boxsim/collision/contact_manifold.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace boxsim {
namespace {

constexpr std::uint32_t kEdgeEdgeContact = 1u << 13;

/// Point depths closer than this fraction of the reference face's larger half extent are
/// treated as equal when choosing the deepest point to keep, and incident vertices that close
/// to a side plane of the reference face as lying on it (unitless). Rounding of a unit box is
/// ~1e-16 m, and a real tilt of 1e-9 rad is not worth tracking.
constexpr double kDepthTieFraction = 1e-9;

/// A vertex of the clipped polygon, with the two lines (incident edge or reference side plane,
/// labels as in the file comment) that meet there: the one before it and the one after it.
/// No default member values: clipping writes a vertex before anything reads it, and the
/// polygons live on the stack of every face contact, where zeroing them would cost time.
struct ClipVertex {
  Vec3 p;
  int inLabel;
  int outLabel;
};

/// A convex polygon of at most 8 vertices: a quad clipped by 4 planes gains at most one vertex
/// per plane. Only the first `count` vertices are set.
struct ClipPolygon {
  std::array<ClipVertex, 8> v;
  int count = 0;
};

/// Sutherland-Hodgman step: keeps the part of `in` where n . p <= offset, written to `out`
/// (not `in`). A vertex within `onPlane` (m) of the plane counts as on it: kept, and never
/// the end of a crossing. A crossing is made only for strictly opposite signs, so a vertex on
/// the plane is never duplicated. Returns false, leaving `out` untouched, when every vertex is
/// already inside: the clipped polygon would be `in` itself, vertex for vertex, so the caller
/// keeps using `in` and no copy is made (the usual case for most side planes of a resting
/// contact).
bool clipToPlane(const ClipPolygon& in, ClipPolygon& out, const Vec3& n, double offset,
                 int planeLabel, double onPlane) {
  // Each vertex's signed distance once, not once as P and again as Q: the same expression on
  // the same point, hence the same bits. Flush faces put incident vertices on the side planes,
  // where rounding scatters them ~1e-17 m to either side; one just outside would be cut off
  // and replaced by two crossings a rounding apart, a fifth point that can crowd a real corner
  // out of the four kept.
  std::array<double, 8> d;
  bool allInside = true;
  for (int k = 0; k < in.count; ++k) {
    d[k] = n.dot(in.v[k].p) - offset;
    if (std::abs(d[k]) <= onPlane) d[k] = 0.0;
    allInside = allInside && d[k] <= 0.0;
  }
  if (allInside) return false;

  out.count = 0;
  for (int k = 0; k < in.count; ++k) {
    const int next = k + 1 < in.count ? k + 1 : 0;
    const ClipVertex& P = in.v[k];
    const ClipVertex& Q = in.v[next];
    const double dP = d[k];
    const double dQ = d[next];
    if (dP <= 0.0) out.v[out.count++] = P;
    if ((dP < 0.0 && dQ > 0.0) || (dP > 0.0 && dQ < 0.0)) {
      ClipVertex& X = out.v[out.count++];
      X.p = P.p + (dP / (dP - dQ)) * (Q.p - P.p);
      // Leaving: the polygon goes on along the plane; entering: along the edge P-Q again.
      X.inLabel = dP < 0.0 ? P.outLabel : planeLabel;
      X.outLabel = dP < 0.0 ? planeLabel : P.outLabel;
    }
  }
  return true;
}

/// A kept point of a face contact before the reduction to four: ContactPoint's fields without
/// its default values, so the 8 slots are not zeroed on every call.
struct FacePoint {
  Vec3 position;
  double depth;
  std::uint32_t featureId;
};

/// Area-like measure of triangle (a, b, q) seen along n: positive when counter-clockwise.
double signedArea(const Vec3& a, const Vec3& b, const Vec3& q, const Vec3& n) {
  return (b - a).cross(q - a).dot(n);
}

/// Chooses 4 of count (5..8) points: the deepest, then the point farthest from it across n,
/// then the one making the largest triangle, then the one adding the most area to it.
/// Depths within depthTie (m) of the deepest count as equally deep, and strict comparisons
/// make the first index win every tie, so flush faces, whose depths differ only by rounding,
/// keep the same points while the clip polygon keeps its shape. Returns the indices in
/// increasing order, so the kept points stay in the clip polygon's cyclic order.
std::array<int, 4> reduceToFour(const std::array<FacePoint, 8>& pts, int count, const Vec3& n,
                                double depthTie) {
  std::array<bool, 8> used{};
  auto take = [&](int k) { used[k] = true; return k; };
  double deepest = pts[0].depth;
  for (int k = 1; k < count; ++k) deepest = std::max(deepest, pts[k].depth);
  int i0 = 0;
  while (pts[i0].depth < deepest - depthTie) ++i0;
  take(i0);
  const Vec3& p0 = pts[i0].position;

  int i1 = -1;
  double best = -1.0;
  for (int k = 0; k < count; ++k) {
    if (used[k]) continue;
    Vec3 d = pts[k].position - p0;
    d -= n * n.dot(d);  // distance within the contact plane, not across it
    if (d.squaredNorm() > best) { best = d.squaredNorm(); i1 = k; }
  }
  take(i1);
  const Vec3& p1 = pts[i1].position;

  int i2 = -1;
  best = -1.0;
  for (int k = 0; k < count; ++k) {
    if (used[k]) continue;
    const double area = std::abs(signedArea(p0, p1, pts[k].position, n));
    if (area > best) { best = area; i2 = k; }
  }
  take(i2);

  // Orient the triangle counter-clockwise about n; a point outside it adds the triangles it
  // makes with the edges it sees, i.e. the edges with a negative signed area.
  std::array<Vec3, 3> tri = {p0, p1, pts[i2].position};
  if (signedArea(tri[0], tri[1], tri[2], n) < 0.0) std::swap(tri[1], tri[2]);
  int i3 = -1;
  best = -1.0;
  for (int k = 0; k < count; ++k) {
    if (used[k]) continue;
    double added = 0.0;
    for (int e = 0; e < 3; ++e)
      added += std::max(0.0, -signedArea(tri[e], tri[(e + 1) % 3], pts[k].position, n));
    if (added > best) { best = added; i3 = k; }
  }
  take(i3);

  std::array<int, 4> keep = {i0, i1, i2, i3};
  std::sort(keep.begin(), keep.end());
  return keep;
}

/// The two faces of a face contact: the reference face, of the box whose axis was chosen,
/// facing the other box, and the incident face, the other box's face most anti-parallel to it.
struct FacePair {
  bool refIsA;   ///< the reference box is A (the axis is a face axis of A)
  int refAxis;   ///< axis of the reference face in its box, 0..2
  bool refPlus;  ///< the reference face lies on the + side of refAxis
  Vec3 nRef;     ///< unit, the reference face's outward normal, towards the incident box
  int incAxis;   ///< axis of the incident face in its box, 0..2
  bool incPlus;  ///< the incident face lies on the + side of incAxis
};

/// The reference and incident faces for the face axis `sat` chose.
FacePair chooseFaces(const Obb& a, const Obb& b, const SeparatingAxisResult& sat) {
  FacePair f;
  f.refIsA = sat.kind == AxisKind::FaceA;
  const Obb& ref = f.refIsA ? a : b;
  const Obb& inc = f.refIsA ? b : a;
  f.refAxis = f.refIsA ? sat.indexA : sat.indexB;
  // The reference face's outward normal, towards the incident box (sat.normal is A to B).
  f.nRef = f.refIsA ? sat.normal : Vec3(-sat.normal);
  f.refPlus = ref.axes.col(f.refAxis).dot(f.nRef) > 0.0;

  // Incident face: the other box's face whose outward normal is most anti-parallel to nRef.
  const std::array<double, 3> incDot = {inc.axes.col(0).dot(f.nRef), inc.axes.col(1).dot(f.nRef),
                                        inc.axes.col(2).dot(f.nRef)};
  f.incAxis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(incDot[k]) > std::abs(incDot[f.incAxis])) f.incAxis = k;
  f.incPlus = incDot[f.incAxis] < 0.0;
  return f;
}

/// Centre (m, world) of the face of `box` on the + (plus) or - side of axis m.
Vec3 faceCentre(const Obb& box, int m, bool plus) {
  return box.center + (plus ? 1.0 : -1.0) * box.halfExtents[m] * box.axes.col(m);
}

/// The incident face of `inc` (axis incAxis, + side when incPlus) as a quad in world
/// coordinates (m), vertex k between edges k-1 and k (file comment diagram).
void incidentQuad(const Obb& inc, int incAxis, bool incPlus, ClipPolygon& quad) {
  static constexpr std::array<double, 4> kSignU = {1.0, -1.0, -1.0, 1.0};
  static constexpr std::array<double, 4> kSignV = {1.0, 1.0, -1.0, -1.0};
  const int iu = (incAxis + 1) % 3, iv = (incAxis + 2) % 3;
  const Vec3 incCenter = faceCentre(inc, incAxis, incPlus);
  quad.count = 4;
  for (int k = 0; k < 4; ++k) {
    quad.v[k].p = incCenter + kSignU[k] * inc.halfExtents[iu] * inc.axes.col(iu) +
                  kSignV[k] * inc.halfExtents[iv] * inc.axes.col(iv);
    quad.v[k].inLabel = (k + 3) % 4;
    quad.v[k].outLabel = k;
  }
}

/// Clips the polygon in buffers[0] against the reference face's side planes, numbered like its
/// edges: 0 +v, 1 -u, 2 -v, 3 +u (labels 4..7; file comment diagram). The face is that of
/// `ref` on side refPlus of refAxis, centred at refCenter (m); vertices within `tie` (m) of a
/// plane count as on it. The two buffers pass the polygon between the clip steps, so no step
/// copies it by value; returns the one holding the result.
const ClipPolygon& clipToSidePlanes(const Obb& ref, int refAxis, const Vec3& refCenter, double tie,
                                    std::array<ClipPolygon, 2>& buffers) {
  const int ru = (refAxis + 1) % 3, rv = (refAxis + 2) % 3;
  const Vec3 u = ref.axes.col(ru);
  const Vec3 v = ref.axes.col(rv);
  const double hu = ref.halfExtents[ru];
  const double hv = ref.halfExtents[rv];
  int current = 0;
  const auto clip = [&](const Vec3& n, double offset, int planeLabel) {
    if (clipToPlane(buffers[current], buffers[1 - current], n, offset, planeLabel, tie))
      current = 1 - current;
  };
  clip(v, v.dot(refCenter) + hv, 4);
  clip(Vec3(-u), -u.dot(refCenter) + hu, 5);
  clip(Vec3(-v), -v.dot(refCenter) + hv, 6);
  clip(u, u.dot(refCenter) + hu, 7);
  return buffers[current];
}

/// The vertices of `poly` below the reference face (through refCenter, outward normal nRef;
/// depth > -margin, m), each placed midway between the two surfaces, with feature id
/// faceBits | its two lines. Writes them to `kept` in polygon order and returns their count.
int pointsBelow(const ClipPolygon& poly, const Vec3& nRef, const Vec3& refCenter, double margin,
                std::uint32_t faceBits, std::array<FacePoint, 8>& kept) {
  int count = 0;
  for (int k = 0; k < poly.count; ++k) {
    const double depth = nRef.dot(refCenter - poly.v[k].p);
    if (depth <= -margin) continue;
    FacePoint& c = kept[count++];
    c.depth = depth;
    c.position = poly.v[k].p + (0.5 * depth) * nRef;
    c.featureId = faceBits | static_cast<std::uint32_t>(poly.v[k].inLabel) |
                  (static_cast<std::uint32_t>(poly.v[k].outLabel) << 3);
  }
  return count;
}

/// Writes `count` kept points to `m`, reduced to four (reduceToFour about nRef, depths within
/// `tie` m equal) when there are more, and sets m.count and m.depth, the deepest point's.
void storeFacePoints(const std::array<FacePoint, 8>& kept, int count, const Vec3& nRef,
                     double tie, ContactManifold& m) {
  const auto put = [&m](int slot, const FacePoint& c) {
    m.points[slot].position = c.position;
    m.points[slot].depth = c.depth;
    m.points[slot].featureId = c.featureId;
  };
  if (count > 4) {
    const std::array<int, 4> keep = reduceToFour(kept, count, nRef, tie);
    for (int k = 0; k < 4; ++k) put(k, kept[keep[k]]);
    count = 4;
  } else {
    for (int k = 0; k < count; ++k) put(k, kept[k]);
  }
  m.count = count;
  if (count > 0) {
    m.depth = m.points[0].depth;
    for (int k = 1; k < count; ++k) m.depth = std::max(m.depth, m.points[k].depth);
  }
}

/// The clipped incident face of a face contact, before the margin picks its points.
struct FaceClip {
  std::array<ClipPolygon, 2> buffers;
  const ClipPolygon* poly = nullptr;  ///< the clip polygon, in one of the buffers
  Vec3 nRef;                          ///< the reference face's outward normal
  Vec3 refCenter;                     ///< m, its centre
  std::uint32_t faceBits = 0;         ///< the feature-id bits of the two faces
  double tie = 0.0;                   ///< m, kDepthTieFraction of the reference face
};

/// Face contact, up to the margin: the incident face of one box clipped against the side planes
/// of the reference face of the other. `clip` must not be copied after (poly points into it).
void clipIncidentFace(const Obb& a, const Obb& b, const SeparatingAxisResult& sat, FaceClip& clip) {
  const FacePair faces = chooseFaces(a, b, sat);
  const Obb& ref = faces.refIsA ? a : b;
  const Obb& inc = faces.refIsA ? b : a;
  const int refFace = 2 * faces.refAxis + (faces.refPlus ? 1 : 0);
  const int incFace = 2 * faces.incAxis + (faces.incPlus ? 1 : 0);

  incidentQuad(inc, faces.incAxis, faces.incPlus, clip.buffers[0]);
  clip.refCenter = faceCentre(ref, faces.refAxis, faces.refPlus);
  clip.nRef = faces.nRef;
  // Rounding-sized distances from a side plane, and depths, count as ties (kDepthTieFraction).
  clip.tie = kDepthTieFraction * std::max(ref.halfExtents[(faces.refAxis + 1) % 3],
                                          ref.halfExtents[(faces.refAxis + 2) % 3]);
  clip.poly = &clipToSidePlanes(ref, faces.refAxis, clip.refCenter, clip.tie, clip.buffers);
  clip.faceBits = (static_cast<std::uint32_t>(incFace) << 6) |
                  (static_cast<std::uint32_t>(refFace) << 9) |
                  ((faces.refIsA ? 0u : 1u) << 12);
}

/// Face contact: clip the incident face of one box against the reference face of the other.
/// Fills the points, count and depth of `m`, whose other fields the caller has set.
void faceContact(const Obb& a, const Obb& b, const SeparatingAxisResult& sat, double margin,
                 ContactManifold& m) {
  FaceClip clip;
  clipIncidentFace(a, b, sat, clip);
  // Keep the points below the reference face, placed midway between the two surfaces.
  std::array<FacePoint, 8> kept;
  const int count = pointsBelow(*clip.poly, clip.nRef, clip.refCenter, margin, clip.faceBits, kept);
  storeFacePoints(kept, count, clip.nRef, clip.tie, m);
}

/// The edge of `box` along axis d farthest along direction n (its support edge), as centre
/// point and edge id (file comment diagram).
void supportEdge(const Obb& box, int d, const Vec3& n, Vec3& mid, std::uint32_t& id) {
  mid = box.center;
  id = static_cast<std::uint32_t>(4 * d);
  for (int s = 1; s <= 2; ++s) {
    const int k = (d + s) % 3;
    const bool plus = box.axes.col(k).dot(n) >= 0.0;
    mid += (plus ? 1.0 : -1.0) * box.halfExtents[k] * box.axes.col(k);
    if (plus) id += static_cast<std::uint32_t>(s);
  }
}

/// Edge-edge contact: the midpoint of the closest points of the support edges of A (along
/// +normal) and B (along -normal). Fills the point, count and depth of `m`.
void edgeContact(const Obb& a, const Obb& b, const SeparatingAxisResult& sat,
                 ContactManifold& m) {
  Vec3 pA, pB;
  std::uint32_t edgeA = 0, edgeB = 0;
  supportEdge(a, sat.indexA, sat.normal, pA, edgeA);
  supportEdge(b, sat.indexB, Vec3(-sat.normal), pB, edgeB);
  const Vec3 dA = a.axes.col(sat.indexA);
  const Vec3 dB = b.axes.col(sat.indexB);
  const double hA = a.halfExtents[sat.indexA];
  const double hB = b.halfExtents[sat.indexB];

  // Closest points pA + s dA, pB + t dB of the two segments (unit directions). The separating
  // axis test only chose this axis if |dA x dB| >= parallelCutoff, so the denominator is > 0.
  const Vec3 r = pA - pB;
  const double cosAB = dA.dot(dB);
  const double c = dA.dot(r);
  const double f = dB.dot(r);
  const double denom = dA.cross(dB).squaredNorm();
  double s = std::clamp((cosAB * f - c) / denom, -hA, hA);
  const double tFree = f + s * cosAB;  // the best t for this s
  const double t = std::clamp(tFree, -hB, hB);
  // Only a clamped t moves the best s; otherwise s is already optimal on its segment.
  if (t != tFree) s = std::clamp(t * cosAB - c, -hA, hA);

  ContactPoint& point = m.points[0];
  point.position = 0.5 * (pA + s * dA + pB + t * dB);
  point.depth = sat.depth;
  point.featureId = kEdgeEdgeContact | edgeA | (edgeB << 4);
  m.count = 1;
  m.depth = sat.depth;
}

}  // namespace

ContactManifold buildContactManifold(const Obb& a, const Obb& b, const SeparatingAxisResult& sat,
                                     double margin) {
  ContactManifold m;
  m.normal = sat.normal;
  m.kind = sat.kind;
  m.depth = sat.depth;
  if (sat.depth <= -margin) return m;
  if (sat.kind == AxisKind::EdgeEdge)
    edgeContact(a, b, sat, m);
  else
    faceContact(a, b, sat, margin, m);
  return m;
}

ClippedContact clipContact(const Obb& a, const Obb& b, const SeparatingAxisResult& sat) {
  ClippedContact c;
  c.sat = sat;
  if (sat.kind == AxisKind::EdgeEdge) {
    ContactManifold m;
    edgeContact(a, b, sat, m);
    c.count = 1;
    c.points[0] = m.points[0];
    return c;
  }
  FaceClip clip;
  clipIncidentFace(a, b, sat, clip);
  // Every vertex of the clip polygon: no margin drops one (a depth is never <= -infinity).
  std::array<FacePoint, 8> all;
  c.count = pointsBelow(*clip.poly, clip.nRef, clip.refCenter,
                        std::numeric_limits<double>::infinity(), clip.faceBits, all);
  for (int k = 0; k < c.count; ++k) c.points[k] = {all[k].position, all[k].depth, all[k].featureId};
  c.referenceNormal = clip.nRef;
  c.tie = clip.tie;
  return c;
}

ContactManifold manifoldWithin(const ClippedContact& clip, double margin) {
  ContactManifold m;
  m.normal = clip.sat.normal;
  m.kind = clip.sat.kind;
  m.depth = clip.sat.depth;
  if (clip.sat.depth <= -margin) return m;
  if (clip.sat.kind == AxisKind::EdgeEdge) {
    m.points[0] = clip.points[0];
    m.count = 1;
    return m;  // depth: sat.depth, as edgeContact sets it
  }
  // pointsBelow's choice, from the depths it computed for every vertex.
  std::array<FacePoint, 8> kept;
  int count = 0;
  for (int k = 0; k < clip.count; ++k) {
    if (clip.points[k].depth <= -margin) continue;
    kept[count++] = {clip.points[k].position, clip.points[k].depth, clip.points[k].featureId};
  }
  storeFacePoints(kept, count, clip.referenceNormal, clip.tie, m);
  return m;
}

std::vector<ContactPoint> contactArea(const Obb& a, const Obb& b, const SeparatingAxisResult& sat,
                                      double margin) {
  // The whole contact area (§3.2): the clip's points within the margin, before the reduction
  // to four (manifoldWithin's choice of points, without it).
  std::vector<ContactPoint> area;
  if (sat.depth <= -margin) return area;
  const ClippedContact clip = clipContact(a, b, sat);
  for (int k = 0; k < clip.count; ++k)
    if (sat.kind == AxisKind::EdgeEdge || !(clip.points[k].depth <= -margin))
      area.push_back(clip.points[k]);
  return area;
}

ContactManifold collideBoxes(const Obb& a, const Obb& b, double margin,
                             const SeparatingAxisParams& params) {
  return buildContactManifold(a, b, separatingAxisTest(a, b, params), margin);
}

namespace {
/// ∫|r| dA over the triangle of the origin and the segment from p to q (2D, m³): with h the
/// distance of the origin from the segment's line and t the signed position along it,
/// ∫ = [t h √(h² + t²) + h³ asinh(t / h)] / 6 between the ends (polar coordinates about the
/// origin, r up to h / cos φ).
double fanIntegral(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const Eigen::Vector2d d = q - p;
  const double length = d.norm();
  if (length == 0.0) return 0.0;
  const Eigen::Vector2d e = d / length;
  const double h = std::abs(p.x() * e.y() - p.y() * e.x());
  if (h == 0.0) return 0.0;
  // asinh(t / h) = ±log((|t| + √(h² + t²)) / h): the square root and the logarithm, which the C
  // libraries compute alike (glibc's and musl's log are one implementation), rather than
  // hypot and asinh, which they round differently now and then (docs/web.md).
  const auto F = [h](double t) {
    const double root = std::sqrt(h * h + t * t);
    const double asinh = std::copysign(std::log((std::abs(t) + root) / h), t);
    return (t * h * root + h * h * h * asinh) / 6.0;
  };
  const double tP = p.dot(e);
  return F(tP + length) - F(tP);
}
}  // namespace

PatchOutline patchOutline(const ContactManifold& m, const Vec3& centre) {
  PatchOutline outline;
  const Vec3 t1 = m.normal.unitOrthogonal();
  const Vec3 t2 = m.normal.cross(t1);
  for (int i = 0; i < m.count; ++i) {
    const Vec3 r = m.points[i].position - centre;
    outline.points[i] = Eigen::Vector2d(r.dot(t1), r.dot(t2));
  }
  outline.count = m.count;
  outline.order = counterClockwiseOrder(outline.points, m.count);
  return outline;
}

double contactPatchRadius(const ContactManifold& m) {
  return contactPatchRadius(m, patchOutline(m, m.centroid()));
}

double contactPatchRadius(const ContactManifold& m, const PatchOutline& outline) {
  if (m.kind == AxisKind::EdgeEdge || m.count < 2) return 0.0;
  if (m.count == 2) return 0.25 * (m.points[1].position - m.points[0].position).norm();
  const std::array<Eigen::Vector2d, 4>& p = outline.points;
  const std::array<int, 4>& order = outline.order;
  double integral = 0.0, area = 0.0;
  for (int k = 0; k < m.count; ++k) {
    const Eigen::Vector2d& a = p[order[k]];
    const Eigen::Vector2d& b = p[order[(k + 1) % m.count]];
    integral += fanIntegral(a, b);
    area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
  }
  return area > 0.0 ? integral / area : 0.0;
}

}  // namespace boxsim
