// Decodes one frame with the installed library; exits 0 when it decodes.
#include <top/top.hpp>

int main() {
  top::ParseResult r = top::parse_exact("#TPUD2wCAP013E");
  if (r.status != top::ParseStatus::frame || !r.frame.checksum_ok) return 1;
  top::Decoded d = top::decode(r.frame, {.dialect = top::Dialect::skydroid});
  if (d.command == nullptr || d.command->ident != "CAP") return 1;
  // The stream decoder, without the tree's detail/ headers.
  top::StreamDecoder dec;
  dec.feed("#TPUD2wCAP013E");
  dec.finish();
  top::StreamItem it;
  if (!dec.next(it) || it.kind != top::ItemKind::frame) return 1;
  // The device rules and the motion table are installed too.
  const top::MotionSpec* gap = top::motion_of(top::Dialect::skydroid, "GAP");
  return gap != nullptr && top::client_address(top::Dialect::topotek, top::Link::network) == 'P'
             ? 0
             : 1;
}
