#include "top/text.hpp"

#include "top/detail/text.hpp"

namespace top {

namespace {
// "\xNN", uppercase hex.
void put_hex_escape(std::string& out, unsigned char c) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  const char b[4] = {'\\', 'x', kHex[c >> 4], kHex[c & 15]};
  out.append(b, 4);
}
}  // namespace

std::optional<std::string> unescape(std::string_view arg, std::string& error) {
  std::string out;
  out.reserve(arg.size());
  for (std::size_t i = 0; i < arg.size(); ++i) {
    char c = arg[i];
    if (c != '\\') {
      out += c;
      continue;
    }
    if (i + 1 >= arg.size()) {
      error = "lone backslash at position " + std::to_string(i);
      return std::nullopt;
    }
    char e = arg[++i];
    switch (e) {
      case 'r':
        out += '\r';
        break;
      case 'n':
        out += '\n';
        break;
      case 't':
        out += '\t';
        break;
      case '0':
        out += '\0';
        break;
      case '\\':
        out += '\\';
        break;
      case 'x': {
        int hi = i + 1 < arg.size() ? hex_value(arg[i + 1]) : -1;
        int lo = i + 2 < arg.size() ? hex_value(arg[i + 2]) : -1;
        if (hi < 0 || lo < 0) {
          error = "\\x at position " + std::to_string(i - 1) + " needs two hex digits";
          return std::nullopt;
        }
        out += static_cast<char>(hi * 16 + lo);
        i += 2;
        break;
      }
      default:
        error = std::string("unknown escape \\") + e + " at position " + std::to_string(i - 1);
        return std::nullopt;
    }
  }
  return out;
}

std::string escape(std::string_view bytes) {
  std::string out;
  out.reserve(bytes.size());
  for (unsigned char c : bytes) {
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
    } else {
      put_hex_escape(out, c);
    }
  }
  return out;
}

std::string markup_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n')
          out += escape(std::string_view(&c, 1));
        else
          out += c;
    }
  }
  return out;
}

std::optional<std::string> bytes_from_utf8(std::string_view utf8) {
  std::string out;
  for (std::size_t i = 0; i < utf8.size();) {
    auto c = static_cast<unsigned char>(utf8[i]);
    if (c < 0x80) {
      out += static_cast<char>(c);
      ++i;
    } else if ((c & 0xFE) == 0xC2 && i + 1 < utf8.size() &&
               (static_cast<unsigned char>(utf8[i + 1]) & 0xC0) == 0x80) {
      const unsigned cp = ((c & 0x1Fu) << 6) | (static_cast<unsigned char>(utf8[i + 1]) & 0x3Fu);
      out += static_cast<char>(cp);
      i += 2;
    } else {
      return std::nullopt;  // past U+00FF, or not UTF-8
    }
  }
  return out;
}

std::string ascii_text(std::string_view message) {
  std::string out;
  out.reserve(message.size());
  for (unsigned char c : message) {
    if (c < 0x80)
      out += static_cast<char>(c);
    else
      put_hex_escape(out, c);
  }
  return out;
}

}  // namespace top
