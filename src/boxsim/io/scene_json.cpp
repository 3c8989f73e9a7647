/// \file
/// The JSON document of a scene's text, with the places of its errors (scene_json.hpp).
#include "boxsim/io/scene_json.hpp"

#include <utility>

namespace boxsim::scene_json {

namespace {

/// Line and column (1-based) of a byte offset in text.
std::pair<int, int> lineColumn(const std::string& text, std::size_t offset) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

[[noreturn]] void throwNonFinite(const std::string& place, const std::string& literal) {
  throw SceneError(place + ": the number " + literal +
                   " is not finite (it overflows a double). Fix: write a finite number");
}

}  // namespace

Json parseJson(const std::string& text, const std::string& source) {
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    const std::size_t at = e.byte > 0 ? e.byte - 1 : 0;
    const std::pair<int, int> lc = lineColumn(text, at);
    const std::string place =
        source + ":" + std::to_string(lc.first) + ":" + std::to_string(lc.second);
    std::string what = e.what();
    const std::size_t colon = what.rfind(": ");
    if (colon != std::string::npos) what = what.substr(colon + 2);
    // NaN and Infinity, as C and JavaScript print them, are no JSON numbers: say so.
    for (const std::string word : {"NaN", "nan", "Infinity", "inf"})
      if (text.compare(at, word.size(), word) == 0)
        throw SceneError(place + ": malformed JSON: " + what + " (" + word +
                         " is not a number in JSON, and a scene takes finite numbers only). Fix: "
                         "write a finite number there");
    throw SceneError(place + ": malformed JSON: " + what + ". Fix: correct the JSON syntax there");
  } catch (const Json::out_of_range& e) {
    // A number literal too large for a double (1e400): nlohmann_json names the literal but not
    // its place, so find it in the text.
    const std::string what = e.what();
    const std::size_t open = what.find("parsing '");
    std::string where;
    if (open != std::string::npos) {
      const std::string literal = what.substr(open + 9, what.find('\'', open + 9) - open - 9);
      const std::size_t at = text.find(literal);
      if (!literal.empty() && at != std::string::npos) {
        const std::pair<int, int> lc = lineColumn(text, at);
        where = ":" + std::to_string(lc.first) + ":" + std::to_string(lc.second);
        throwNonFinite(source + where, literal);
      }
    }
    throw SceneError(source + ": malformed JSON: " + what + ". Fix: correct the number it names");
  } catch (const Json::exception& e) {
    throw SceneError(source + ": malformed JSON: " + std::string(e.what()) +
                     ". Fix: correct the JSON there");
  }
}

}  // namespace boxsim::scene_json
