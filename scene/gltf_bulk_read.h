#pragma once
// The element readers of scene/gltf_bulk.cpp: a node, a light, a scene root, and the checks
// and number rules they share, over simdjson's on-demand values. Internal to scene/.
#include <simdjson.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"
#include "scene/gltf_bulk.h"

namespace manylight::gltf::bulk {

namespace od = simdjson::ondemand;

// Text that is not JSON: left to tinygltf to name.
struct Syntax {
  simdjson::error_code code;
};

inline bool isTypeError(simdjson::error_code e) {
  return e == simdjson::INCORRECT_TYPE || e == simdjson::NUMBER_OUT_OF_RANGE;
}

// Throws SceneError(message()) when `e` says the value has the wrong type, Syntax when the
// text is broken. `message` is called only on failure.
template <typename F>
void check(simdjson::error_code e, const F& message) {
  if (e == simdjson::SUCCESS) return;
  if (isTypeError(e)) throw SceneError(message());
  throw Syntax{e};
}

inline void check(simdjson::error_code e) {
  if (e != simdjson::SUCCESS) throw Syntax{e};
}

// JSON's number grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
bool isJsonNumber(std::string_view t);

template <typename F>
double number(od::value v, const F& message) {
  double d = 0.0;
  const simdjson::error_code e = v.get_double().get(d);
  if (e == simdjson::NUMBER_ERROR) {
    // Beyond double's range: read as strtod reads it (±infinity, or 0), which the checks of
    // the values then refuse in their own words, as for any other non-finite value.
    std::string token(v.raw_json_token());
    while (!token.empty() && (token.back() == ' ' || token.back() == '\n' || token.back() == '\r' ||
                              token.back() == '\t'))
      token.pop_back();
    if (!isJsonNumber(token)) throw Syntax{e};
    return std::strtod(token.c_str(), nullptr);
  }
  check(e, message);
  return d;
}

// An array of numbers into out[0, capacity); returns how many the array holds.
template <typename F>
std::size_t numbers(od::value v, double* out, std::size_t capacity, const F& message) {
  od::array a;
  check(v.get_array().get(a), message);
  std::size_t n = 0;
  for (auto element : a) {
    od::value x;
    check(element.get(x));
    const double d = number(x, message);
    if (n < capacity) out[n] = d;
    ++n;
  }
  return n;
}

template <typename F>
void exactNumbers(od::value v, double* out, std::size_t count, const F& message) {
  if (numbers(v, out, count, message) != count) throw SceneError(message());
}

// An index: an integer (also written as 2.0) that fits an int; negative ones are kept for
// the checks that name them.
template <typename F>
std::int32_t index(od::value v, const F& message) {
  std::int64_t i = 0;
  simdjson::error_code e = v.get_int64().get(i);
  if (e == simdjson::INCORRECT_TYPE) {
    double d = 0.0;
    check(v.get_double().get(d), message);
    if (d != std::floor(d) || std::fabs(d) > 2147483647.0) throw SceneError(message());
    return std::int32_t(d);
  }
  check(e, message);
  if (i < std::numeric_limits<std::int32_t>::min() || i > std::numeric_limits<std::int32_t>::max())
    throw SceneError(message());
  return std::int32_t(i);
}

std::string str(std::size_t i);

// A field's key as written between its quotes, read in place (its escapes checked): un-
// escaping every key would copy them all into the parser's string buffer, which grows with
// the document. A key written with escapes matches none of glTF's, and is read as an
// unknown property.
std::string_view keyOf(simdjson::simdjson_result<od::field>& field);

// Reads a value the loader does not use (a name, extras, another extension) to its end, so
// that broken JSON inside the arrays taken from tinygltf is still refused as broken.
void validate(od::value v, int depth = 0);

bool isArray(od::value v);

// Node `i`; its children are appended to out.children and a matrix to out.matrices (the
// record's firstChild and matrix index those).
NodeRecord readNode(od::value v, std::size_t i, BulkArrays& out);
// Light `i`; a type glTF does not define goes to out.otherTypes.
LightRecord readLight(od::value v, std::size_t i, BulkArrays& out);
// A root of a scene, as tinygltf's integer arrays take one: a JSON integer, cast to int.
// After the first value that is not one, tinygltf keeps none; `stopped` says so.
void readSceneNode(od::value x, std::vector<std::int32_t>& roots, bool& stopped);

}  // namespace manylight::gltf::bulk
