#include "json_comments.hpp"

namespace drape::materials_detail {

std::string blank_json_comments(const std::string& text) {
  std::string out = text;
  enum class State { Code, String, LineComment, BlockComment } state = State::Code;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const char c = out[i];
    const char next = i + 1 < out.size() ? out[i + 1] : '\0';
    switch (state) {
      case State::Code:
        if (c == '"') {
          state = State::String;
        } else if (c == '/' && next == '/') {
          state = State::LineComment;
          out[i] = ' ';
        } else if (c == '/' && next == '*') {
          state = State::BlockComment;
          out[i] = out[i + 1] = ' ';
          ++i;
        } else if (c == '\t') {
          out[i] = ' ';
        }
        break;
      case State::String:
        if (c == '\\')
          ++i;  // an escaped character, possibly a quote
        else if (c == '"' || c == '\n')
          state = State::Code;  // a newline ends a broken string: let the parser report it there
        break;
      case State::LineComment:
        if (c == '\n')
          state = State::Code;
        else if (c != '\r')
          out[i] = ' ';
        break;
      case State::BlockComment:
        if (c == '*' && next == '/') {
          out[i] = out[i + 1] = ' ';
          ++i;
          state = State::Code;
        } else if (c != '\n' && c != '\r') {
          out[i] = ' ';
        }
        break;
    }
  }
  return out;
}

}  // namespace drape::materials_detail
