#pragma once
// Text inside SVG (XML) elements: the three characters markup would take.
#include <string>

namespace drape {

inline std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (ch == '<') out += "&lt;";
    else if (ch == '>') out += "&gt;";
    else if (ch == '&') out += "&amp;";
    else out += ch;
  }
  return out;
}

}  // namespace drape
