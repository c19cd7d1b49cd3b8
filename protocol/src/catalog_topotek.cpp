// The Topotek SIP "Udp&uart-Protocol" V1.1.3 command table (seeds/001_...).
// Section numbers are the document's own (chapter.number).
#include "catalog_data.hpp"

namespace top::detail {
namespace {

constexpr ModelSet sip = model_bit(Model::sip);

// 4.1 PTZ: 06/07 are lock/follow here, the reverse of SkyDroid.
constexpr EnumValue kPtz[] = {
    {0x00, "stop"},   {0x01, "up"},     {0x02, "down"},
    {0x03, "left"},   {0x04, "right"},  {0x05, "center"},
    {0x06, "lock"},   {0x07, "follow"}, {0x08, "toggle_follow_lock"},
    {0x09, "calibrate"}, {0x0A, "point_down"},
};
constexpr FieldSpec kPtzFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kPtz},
};
constexpr FormSpec kPtzForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kPtzFields},
};

constexpr CommandSpec kTable[] = {
    {.ident = "PTZ", .dialect = Dialect::topotek, .address = 'G',
     .title = "gimbal control", .section = "Topotek 4.1", .models = sip,
     .forms = kPtzForms},
};

}  // namespace

std::span<const CommandSpec> topotek_table() noexcept { return kTable; }

}  // namespace top::detail
