/// \file
/// Reading a scene file's JSON (scene.cpp): the document, with the line and column of a syntax
/// error, and each value with its path, so that every error names the file, the place and the
/// fix. Internal to the io layer: not installed.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>

#include "boxsim/core/math.hpp"
#include "boxsim/io/scene.hpp"

namespace boxsim::scene_json {

/// The JSON document type (nlohmann-json).
using Json = nlohmann::json;

/// Range of one kind of scene number, with its unit for messages.
struct Range {
  double lo;         ///< smallest magnitude allowed (0: none)
  double hi;         ///< largest magnitude allowed
  const char* unit;  ///< SI unit, for messages
};
// The ranges every number of a scene must lie in. Finite is not enough: the techniques form
// products such as the inertia m h^2, its inverse, the momenta m v and I w and the squares of
// lengths in the separating-axis test, and far-out inputs make these underflow to 0 or overflow
// to infinity (half extents of 1e-200 m give an inertia of 0, an infinite inverse inertia and a
// NaN state after one step). Within these ranges every such product is a finite, non-zero
// double with over a hundred orders of magnitude to spare; the techniques' own tolerances are
// tuned for bodies of centimetres to metres, far inside them.
constexpr Range kSizeRange{1e-6, 1e6, "m"};      ///< half extents, cube sizes, spacing, ground
constexpr Range kMassRange{1e-6, 1e6, "kg"};     ///< masses
constexpr Range kCoordinateRange{0.0, 1e6, "m"};  ///< positions, origins, centres, gaps, height
constexpr Range kSpeedRange{0.0, 1e6, "m/s"};     ///< velocities and the clump's speed
constexpr Range kAngularSpeedRange{0.0, 1e6, "rad/s"};  ///< angular velocities
constexpr Range kGravityRange{0.0, 1e6, "m/s^2"};       ///< gravity components

/// One JSON value with its path, for reading values with errors that say where they were.
class Node {
 public:
  /// `value` at `path` (e.g. "/bodies/2/mass") of the scene named `source`; keeps references
  /// to value and source, which must outlive the node.
  Node(const Json& value, std::string path, const std::string& source)
      : value_(value), path_(std::move(path)), source_(source) {}

  /// Throws SceneError "source: path: problem. Fix: fix".
  [[noreturn]] void fail(const std::string& problem, const std::string& fix) const {
    throw SceneError(source_ + ": " + (path_.empty() ? "/" : path_) + ": " + problem +
                     ". Fix: " + fix);
  }

  /// The JSON path of the value, "" for the document.
  const std::string& path() const { return path_; }
  /// Whether the object has `key`.
  bool has(const char* key) const { return value_.contains(key); }
  /// The value of `key` (which must exist), with its path.
  Node at(const char* key) const { return Node(value_.at(key), path_ + "/" + key, source_); }

  /// Whether the value is a JSON object.
  bool isObject() const { return value_.is_object(); }

  /// Fails unless the value is an object; `what` names it in the message.
  void requireObject(const std::string& what) const {
    if (!value_.is_object()) fail("expected " + what + " (a JSON object)", "write { ... } here");
  }

  /// Fails at the first key not in `known`, listing the known ones.
  void allowKeys(std::initializer_list<const char*> known) const {
    for (auto it = value_.begin(); it != value_.end(); ++it) {
      const bool ok = std::any_of(known.begin(), known.end(),
                                  [&](const char* k) { return it.key() == k; });
      if (ok) continue;
      std::string list;
      for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
      Node(it.value(), path_ + "/" + it.key(), source_)
          .fail("unknown key \"" + it.key() + "\"", "use one of: " + list);
    }
  }

  /// A finite number.
  double number() const {
    if (!value_.is_number()) fail("expected a number, got " + describe(), "write a number");
    const double x = value_.get<double>();
    if (!std::isfinite(x)) fail("the number is not finite", "write a finite number");
    return x;
  }
  /// A number of magnitude at most range.hi (range.lo is not checked: zero is allowed).
  double bounded(const Range& range) const {
    const double x = number();
    if (std::abs(x) > range.hi)
      fail("must lie within +-" + text(range.hi) + " " + range.unit + " (got " + text(x) + ")",
           "give a value in that range; scenes are limited to it so that the physics stays "
           "within double precision");
    return x;
  }
  /// A number in [range.lo, range.hi].
  double positive(const Range& range) const {
    const double x = number();
    if (!(x > 0.0))
      fail("must be > 0 " + std::string(range.unit) + " (got " + text(x) + ")",
           "give a positive value");
    if (x < range.lo || x > range.hi)
      fail("must lie in [" + text(range.lo) + ", " + text(range.hi) + "] " + range.unit +
               " (got " + text(x) + ")",
           "give a value in that range; scenes are limited to it so that the physics stays "
           "within double precision");
    return x;
  }
  /// A number >= 0, and at most `limit` when one is given.
  double nonNegative(const char* unit, const Range* limit = nullptr) const {
    const double x = limit ? bounded(*limit) : number();
    if (x < 0.0)
      fail("must be >= 0 " + std::string(unit) + " (got " + text(x) + ")",
           "give zero or a positive value");
    return x;
  }
  /// A whole number from 1 to 1000000.
  int count() const {
    const double x = number();
    if (x < 1.0 || x != std::floor(x) || x > 1e6)
      fail("must be a whole number from 1 to 1000000 (got " + text(x) + ")",
           "give a positive whole count");
    return static_cast<int>(x);
  }
  /// true or false.
  bool boolean() const {
    if (!value_.is_boolean()) fail("expected true or false, got " + describe(), "write true or false");
    return value_.get<bool>();
  }
  /// A non-empty name without white space.
  std::string name() const {
    if (!value_.is_string()) fail("expected a string, got " + describe(), "write a quoted name");
    const std::string s = value_.get<std::string>();
    const bool blank = std::any_of(s.begin(), s.end(), [](unsigned char c) { return std::isspace(c); });
    if (s.empty() || blank) fail("names must be non-empty and free of white space", "use e.g. \"box_1\"");
    return s;
  }
  /// Any string.
  std::string string() const {
    if (!value_.is_string()) fail("expected a string, got " + describe(), "write a quoted string");
    return value_.get<std::string>();
  }
  /// [x, y, z] of finite numbers; with a range, each of magnitude at most range->hi.
  Vec3 vec3(const Range* range = nullptr) const {
    if (!value_.is_array() || value_.size() != 3)
      fail("expected an array of 3 numbers, got " + describe(), "write [x, y, z]");
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      const Node component(value_[i], path_ + "/" + std::to_string(i), source_);
      v[i] = range ? component.bounded(*range) : component.number();
    }
    return v;
  }
  /// vec3() with each component of magnitude at most range.hi.
  Vec3 vec3(const Range& range) const { return vec3(&range); }
  /// [x, y, z], each component in [range.lo, range.hi] and > 0 (half extents).
  Vec3 positiveVec3(const Range& range) const {
    const Vec3 v = vec3();
    for (int i = 0; i < 3; ++i) {
      const Node component(value_[i], path_ + "/" + std::to_string(i), source_);
      if (!(v[i] > 0.0))
        component.fail("must be > 0 " + std::string(range.unit) + " (got " + text(v[i]) + ")",
                       "give positive half extents");
      component.positive(range);
    }
    return v;
  }
  /// [w, x, y, z], non-zero, normalised.
  Quat quaternion() const {
    if (!value_.is_array() || value_.size() != 4)
      fail("expected an array of 4 numbers [w, x, y, z], got " + describe(), "write [w, x, y, z]");
    double c[4];
    for (int i = 0; i < 4; ++i) c[i] = Node(value_[i], path_ + "/" + std::to_string(i), source_).number();
    Quat q(c[0], c[1], c[2], c[3]);
    if (q.norm() < 1e-12) fail("the quaternion must not be zero", "give a unit quaternion, e.g. [1, 0, 0, 0]");
    q.normalize();
    return q;
  }
  /// [x, y, z], not the zero vector; `what` names it in the message.
  Vec3 nonZeroVec3(const char* what) const {
    const Vec3 v = vec3();
    if (v.norm() == 0.0) fail(std::string(what) + " must not be the zero vector", "give a direction");
    return v;
  }

 private:
  std::string describe() const {
    std::string d = value_.dump();
    if (d.size() > 40) d = d.substr(0, 37) + "...";
    return std::string(value_.type_name()) + " " + d;
  }
  // Shortest round-trip text, so that a value just outside a range is not printed as its bound.
  static std::string text(double x) { return shortestText(x); }

  const Json& value_;
  std::string path_;
  const std::string& source_;
};

/// The JSON document of a scene's text (`source` names it in messages). Throws SceneError
/// naming the line and column of a syntax error, or the place of a number literal too large
/// for a double.
Json parseJson(const std::string& text, const std::string& source);

}  // namespace boxsim::scene_json
