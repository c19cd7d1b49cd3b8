// Decodes one frame with the installed library; exits 0 when it decodes.
#include <top/top.hpp>

int main() {
  top::ParseResult r = top::parse_exact("#TPUD2wCAP013E");
  if (r.status != top::ParseStatus::frame || !r.frame.checksum_ok) return 1;
  top::Decoded d = top::decode(r.frame, {.dialect = top::Dialect::skydroid});
  return d.command != nullptr && d.command->ident == "CAP" ? 0 : 1;
}
