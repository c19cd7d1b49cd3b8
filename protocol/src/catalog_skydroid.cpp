// The SkyDroid "TOP protocol" V1.1.5 command table (seeds/000_...).
// Section numbers are the document's own.
#include "catalog_data.hpp"

namespace top::detail {
namespace {

constexpr ModelSet c10 = model_bit(Model::c10);
constexpr ModelSet c10pro = model_bit(Model::c10pro);
constexpr ModelSet c12 = model_bit(Model::c12);
constexpr ModelSet c13 = model_bit(Model::c13);
constexpr ModelSet c20 = model_bit(Model::c20);

// 3.1 PTZ
constexpr EnumValue kPtz[] = {
    {0x00, "stop"},          {0x01, "up"},
    {0x02, "down"},          {0x03, "left"},
    {0x04, "right"},         {0x05, "center"},
    {0x06, "follow"},        {0x07, "lock"},
    {0x08, "toggle_follow_lock"}, {0x09, "calibrate"},
    {0x0A, "hanging_mode"},  {0x0B, "inverted_mode"},
    {0x0C, "level_calibration"}, {0x0D, "vertical_calibration"},
    {0x0E, "trim_x_plus"},   {0x0F, "trim_x_minus"},
    {0x10, "trim_y_plus"},   {0x11, "trim_y_minus"},
    {0x12, "trim_z_plus"},   {0x13, "trim_z_minus"},
    {0x14, "clear_trim"},
};
constexpr FieldSpec kPtzFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kPtz},
};
constexpr FormSpec kPtzForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kPtzFields},
};

// 3.3.1 GAY (angle control)
constexpr FieldSpec kAngleFields[] = {
    {.name = "angle", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01,
     .unit = "deg", .min = -90, .max = 90},
    {.name = "speed", .kind = FieldKind::hex_u, .width = 2, .scale = 0.1,
     .unit = "deg/s", .min = 0, .max = 9.9},
};
constexpr FormSpec kAngleForms[] = {
    {.control = 'w', .min_length = 6, .max_length = 6, .fields = kAngleFields},
};

constexpr CommandSpec kTable[] = {
    {.ident = "PTZ", .dialect = Dialect::skydroid, .address = 'G',
     .title = "gimbal control", .section = "SkyDroid 3.1",
     .models = c10 | c10pro | c12 | c20, .forms = kPtzForms},
    {.ident = "GAY", .dialect = Dialect::skydroid, .address = 'G',
     .title = "gimbal yaw angle", .section = "SkyDroid 3.3.1",
     .models = c10 | c10pro | c12 | c20, .forms = kAngleForms,
     .note = "the example #TPUG6wGAYEF073288 carries a checksum computed "
             "with the #tp header"},
};

}  // namespace

std::span<const CommandSpec> skydroid_table() noexcept { return kTable; }

}  // namespace top::detail
