// The SkyDroid "TOP protocol" V1.1.5 command table (seeds/000_...).
// Section numbers are the document's own.
#include "catalog_data.hpp"

// Designated initializers leave the other members at their defaults on
// purpose; GCC before 13 warns about each omitted member under -Wextra.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace top::detail {
namespace {

// Sections without a "supported models" line: every model of the document.
constexpr ModelSet all = c10 | c10pro | c12 | c13 | c20;

// ---------------------------------------------------------------------------
// Shared pieces

// A read request: data "00".
constexpr FieldSpec kQueryFields[] = {
    {.name = "query", .kind = FieldKind::hex_u, .width = 2},
};

// Identifiers listed in appendix I only: no layout.
constexpr FieldSpec kRawFields[] = {
    {.name = "data", .kind = FieldKind::raw, .width = 0},
};
constexpr FormSpec kAppendixForms[] = {
    {.control = 'r', .role = Role::any, .min_length = 0, .max_length = 255, .fields = kRawFields},
    {.control = 'w', .role = Role::any, .min_length = 0, .max_length = 255, .fields = kRawFields},
};

constexpr EnumValue kEnable[] = {
    {0x00, "disable"},
    {0x01, "enable"},
};

// ---------------------------------------------------------------------------
// 2.3.2 ERE (invalid command reply)
constexpr FieldSpec kEreFields[] = {
    {.name = "code", .kind = FieldKind::text, .width = 0, .note = "\"!!\" in the only example"},
};
constexpr FormSpec kEreForms[] = {
    {.control = 'w',
     .role = Role::response,
     .min_length = 0,
     .max_length = 15,
     .fields = kEreFields},
};

// 3.1 PTZ
constexpr EnumValue kPtz[] = {
    {0x00, "stop"},
    {0x01, "up"},
    {0x02, "down"},
    {0x03, "left"},
    {0x04, "right"},
    {0x05, "center"},
    {0x06, "follow"},
    {0x07, "lock"},
    {0x08, "toggle_follow_lock"},
    {0x09, "calibrate"},
    {0x0A, "hanging_mode"},
    {0x0B, "inverted_mode"},
    {0x0C, "level_calibration"},
    {0x0D, "vertical_calibration"},
    {0x0E, "trim_x_plus"},
    {0x0F, "trim_x_minus"},
    {0x10, "trim_y_plus"},
    {0x11, "trim_y_minus"},
    {0x12, "trim_z_plus"},
    {0x13, "trim_z_minus"},
    {0x14, "clear_trim"},
};
constexpr FieldSpec kPtzFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kPtz},
};
constexpr FormSpec kPtzForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kPtzFields},
};

// 3.2 GSY/GSP/GSR/GSM (speed): 8-bit signed steps of 0.5 deg/s.
constexpr FieldSpec kSpeedFields[] = {
    {.name = "speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 0.5,
     .unit = "deg/s",
     .min = -63.5,
     .max = 63.5,
     .note = "-127..127 steps; yaw right positive, pitch up positive"},
};
constexpr FormSpec kSpeedForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kSpeedFields},
};
constexpr FieldSpec kSpeedYawPitchFields[] = {
    {.name = "yaw_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 0.5,
     .unit = "deg/s",
     .min = -63.5,
     .max = 63.5},
    {.name = "pitch_speed",
     .kind = FieldKind::hex_s,
     .width = 2,
     .scale = 0.5,
     .unit = "deg/s",
     .min = -63.5,
     .max = 63.5},
};
constexpr FormSpec kSpeedYawPitchForms[] = {
    {.control = 'w', .min_length = 4, .max_length = 4, .fields = kSpeedYawPitchFields},
};

// 3.3.1 GAY/GAP/GAR (angle control)
constexpr FieldSpec kAngleFields[] = {
    {.name = "angle",
     .kind = FieldKind::hex_s,
     .width = 4,
     .scale = 0.01,
     .unit = "deg",
     .min = -90,
     .max = 90},
    {.name = "speed",
     .kind = FieldKind::hex_u,
     .width = 2,
     .scale = 0.1,
     .unit = "deg/s",
     .min = 0,
     .max = 9.9},
};
constexpr FormSpec kAngleForms[] = {
    {.control = 'w', .min_length = 6, .max_length = 6, .fields = kAngleFields},
};
// 3.3.1 GAM (yaw & pitch angle)
constexpr FieldSpec kAngleYawPitchFields[] = {
    {.name = "yaw",
     .kind = FieldKind::hex_s,
     .width = 4,
     .scale = 0.01,
     .unit = "deg",
     .min = -90,
     .max = 90},
    {.name = "yaw_speed",
     .kind = FieldKind::hex_u,
     .width = 2,
     .scale = 0.1,
     .unit = "deg/s",
     .min = 0,
     .max = 9.9},
    {.name = "pitch",
     .kind = FieldKind::hex_s,
     .width = 4,
     .scale = 0.01,
     .unit = "deg",
     .min = -90,
     .max = 90},
    {.name = "pitch_speed",
     .kind = FieldKind::hex_u,
     .width = 2,
     .scale = 0.1,
     .unit = "deg/s",
     .min = 0,
     .max = 9.9},
};
constexpr FormSpec kAngleYawPitchForms[] = {
    {.control = 'w', .min_length = 12, .max_length = 12, .fields = kAngleYawPitchFields},
};

// 3.3.2.1 GAA (attitude push rate)
constexpr EnumValue kGaaLabels[] = {
    {0x00, "off"},
};
constexpr FieldSpec kGaaFields[] = {
    {.name = "rate",
     .kind = FieldKind::hex_u,
     .width = 2,
     .unit = "Hz",
     .min = 0,
     .max = 100,
     .enums = kGaaLabels,
     .note = "00 off; 01-64 hex = 1-100 Hz"},
};
constexpr FormSpec kGaaForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kGaaFields},
};

// 3.3.2.2 GAC (attitude push) and 3.3.6.2 FAI (flight controller attitude)
constexpr FieldSpec kAttitudeFields[] = {
    {.name = "yaw", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
    {.name = "pitch", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
    {.name = "roll", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
};
constexpr FormSpec kGacForms[] = {
    {.control = 'r',
     .role = Role::any,
     .min_length = 12,
     .max_length = 12,
     .fields = kAttitudeFields,
     .note = "pushed after GAA; the document writes it #TPUGCrGAC (U first)"},
};
// The field's FAI: the attitude and a mode byte, 14 chars, as ArduPilot's
// SkyDroid driver sends it (AP_Mount_SkyDroid.cpp @ c5aa8452,
// send_attitude_to_gimbal(): "%04X%04X%04X%02X").
constexpr EnumValue kFaiMode[] = {
    {0x00, "hover"},
    {0x01, "fixed_wing"},
};
constexpr FieldSpec kFaiModeFields[] = {
    {.name = "yaw", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
    {.name = "pitch", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
    {.name = "roll", .kind = FieldKind::hex_s, .width = 4, .scale = 0.01, .unit = "deg"},
    {.name = "mode",
     .kind = FieldKind::enum_hex,
     .width = 2,
     .enums = kFaiMode,
     .note = "1 fixed-wing, 0 copter/hover (AP_Mount_SkyDroid.cpp: \"SkyDroid's own documented "
             "field for this command\"; its author does not know what it changes); SkyDroid "
             "3.3.6.2 (V1.1.5) has no such field"},
};
constexpr FormSpec kFaiForms[] = {
    {.control = 'w',
     .role = Role::any,
     .min_length = 12,
     .max_length = 12,
     .fields = kAttitudeFields},
    {.control = 'w',
     .role = Role::any,
     .min_length = 14,
     .max_length = 14,
     .fields = kFaiModeFields,
     .note = "the attitude and a mode byte",
     .evidence = "AP_Mount_SkyDroid.cpp @ c5aa8452 (ArduPilot PR #34155) "
                 "send_attitude_to_gimbal(): yaw, pitch, roll (0.01 deg) and the mode as "
                 "\"%04X%04X%04X%02X\", 10 times a second, its comment's sample #tpUG0EwFAI; "
                 "AP_Mount_Backend_TPFrame.cpp @ 4e7781a1 send_variablelen_packet() writes the "
                 "length as one hex char: #tpUGEwFAI + 14 chars"},
};

// 3.3.4 SUM (tracking)
constexpr EnumValue kSum[] = {
    {0x00, "stop"},
    {0x01, "confirm"},
};
constexpr FieldSpec kSumFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kSum},
};
constexpr FormSpec kSumForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kSumFields},
};

// 3.3.5 GOT (target position, 1280x720 frame)
constexpr FieldSpec kGotFields[] = {
    {.name = "x", .kind = FieldKind::hex_u, .width = 4, .unit = "px", .min = 0, .max = 1280},
    {.name = "y", .kind = FieldKind::hex_u, .width = 4, .unit = "px", .min = 0, .max = 720},
};
constexpr FormSpec kGotForms[] = {
    {.control = 'w', .min_length = 8, .max_length = 8, .fields = kGotFields},
};

// 3.3.6.1 FAE
constexpr FieldSpec kFaeFields[] = {
    {.name = "state", .kind = FieldKind::enum_hex, .width = 2, .enums = kEnable},
};
constexpr FormSpec kFaeForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kFaeFields},
};

// ---------------------------------------------------------------------------
// 4.1 REC
constexpr EnumValue kRecAction[] = {
    {0x00, "stop"},
    {0x01, "start"},
    {0x0A, "toggle"},
};
constexpr EnumValue kRecState[] = {
    {0x00, "not_recording"},
    {0x01, "recording"},
};
constexpr FieldSpec kRecActionFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kRecAction},
};
constexpr FieldSpec kRecStateFields[] = {
    {.name = "state", .kind = FieldKind::enum_hex, .width = 2, .enums = kRecState},
};
constexpr FormSpec kRecForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kRecActionFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kRecStateFields},
};

// 4.2 CAP
constexpr EnumValue kCap[] = {
    {0x01, "capture"},
};
constexpr FieldSpec kCapFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kCap},
};
constexpr FormSpec kCapForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kCapFields},
};

// 4.3 VID (recording resolution), one char per lens
constexpr EnumValue kVid[] = {
    {'0', "res_720p"}, {'1', "res_1080p"}, {'2', "res_2k"}, {'3', "res_4k"}, {'N', "none"},
};
constexpr FieldSpec kVidFields[] = {
    {.name = "secondary_lens",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kVid,
     .note = "x0: used with two visible-light lenses only"},
    {.name = "main_lens",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kVid,
     .note = "x1: the only one used with a single lens"},
};
constexpr FormSpec kVidForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kVidFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kVidFields},
};

// 4.4 SDC
constexpr EnumValue kSdcQuery[] = {
    {0x00, "capacity"},
};
constexpr FieldSpec kSdcQueryFields[] = {
    {.name = "query", .kind = FieldKind::enum_hex, .width = 2, .enums = kSdcQuery},
};
constexpr FieldSpec kSdcFields[] = {
    {.name = "free", .kind = FieldKind::hex_u, .width = 5, .unit = "MB"},
    {.name = "total", .kind = FieldKind::hex_u, .width = 5, .unit = "MB"},
};
constexpr FormSpec kSdcForms[] = {
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kSdcQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 10,
     .max_length = 10,
     .fields = kSdcFields,
     .note = "all zero: no memory card",
     .none = "0000000000"},
};

// 4.5.1 AWB, one char per lens
constexpr EnumValue kAwb[] = {
    {'0', "auto"},
    {'1', "night"},
    {'2', "incandescent"},
    {'3', "fluorescent"},
    {'4', "warm_fluorescent"},
    {'5', "daylight"},
    {'6', "cloudy_daylight"},
    {'7', "twilight"},
    {'8', "shade"},
    {'A', "awb_plus"},
    {'B', "awb_minus"},
    {'N', "none"},
};
constexpr FieldSpec kAwbFields[] = {
    {.name = "secondary_lens",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kAwb,
     .note = "x0: used with two visible-light lenses only"},
    {.name = "main_lens",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kAwb,
     .note = "x1: the only one used with a single lens"},
};
constexpr FormSpec kAwbForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kAwbFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kAwbFields},
};

// 4.5.2 IQE (image parameters)
constexpr EnumValue kIqeStyle[] = {
    {'0', "custom"},
    {'1', "standard"},
    {'2', "bright"},
    {'3', "vivid"},
};
constexpr FieldSpec kIqeFields[] = {
    {.name = "lens_id", .kind = FieldKind::hex_u, .width = 1},
    {.name = "style", .kind = FieldKind::enum_char, .width = 1, .enums = kIqeStyle},
    {.name = "hue", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 255},
    {.name = "brightness", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 255},
    {.name = "saturation", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 255},
    {.name = "contrast", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 255},
    {.name = "sharpness", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 255},
};
constexpr FormSpec kIqeForms[] = {
    {.control = 'w', .min_length = 12, .max_length = 12, .fields = kIqeFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 12,
     .max_length = 12,
     .fields = kIqeFields},
};

// 4.6 TIM: hhmmss.ss then DDMMYY (example 142832.00031218)
constexpr FieldSpec kTimFields[] = {
    {.name = "hour", .kind = FieldKind::dec_u, .width = 2, .min = 0, .max = 23},
    {.name = "minute", .kind = FieldKind::dec_u, .width = 2, .min = 0, .max = 59},
    {.name = "second",
     .kind = FieldKind::number,
     .width = 5,
     .unit = "s",
     .min = 0,
     .max = 59.99,
     .note = "ss.ss"},
    {.name = "day", .kind = FieldKind::dec_u, .width = 2, .min = 1, .max = 31},
    {.name = "month", .kind = FieldKind::dec_u, .width = 2, .min = 1, .max = 12},
    {.name = "year",
     .kind = FieldKind::dec_u,
     .width = 2,
     .min = 0,
     .max = 99,
     .note = "two digits (18 = 2018)"},
};
constexpr FormSpec kTimForms[] = {
    {.control = 'w', .min_length = 15, .max_length = 15, .fields = kTimFields},
};

// 4.7 DZM (digital zoom)
constexpr EnumValue kDzm[] = {
    {0x01, "x1"}, {0x02, "x2"}, {0x03, "x3"}, {0x04, "x4"}, {0x0A, "zoom_in"}, {0x0B, "zoom_out"},
};
constexpr FieldSpec kDzmFields[] = {
    {.name = "zoom", .kind = FieldKind::enum_hex, .width = 2, .enums = kDzm},
};
constexpr FormSpec kDzmForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kDzmFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kDzmFields},
};

// 4.8 IMG (thermal palette)
constexpr EnumValue kImg[] = {
    {0x01, "white_hot"}, {0x03, "sepia"},     {0x04, "ironbow"},   {0x05, "rainbow"},
    {0x06, "night"},     {0x07, "aurora"},    {0x08, "red_hot"},   {0x09, "jungle"},
    {0x0A, "medical"},   {0x0B, "black_hot"}, {0x0C, "glory_hot"},
};
constexpr FieldSpec kImgFields[] = {
    {.name = "palette", .kind = FieldKind::enum_hex, .width = 2, .enums = kImg},
};
constexpr FormSpec kImgForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kImgFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kImgFields},
};

// 4.9 IPV/GTW/DNS/BNS (network addresses as dotted text)
constexpr FieldSpec kAddressFields[] = {
    {.name = "address", .kind = FieldKind::text, .width = 0},
};
constexpr FormSpec kAddressReadWriteForms[] = {
    {.control = 'w', .min_length = 7, .max_length = 15, .fields = kAddressFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 7,
     .max_length = 15,
     .fields = kAddressFields},
};
constexpr FormSpec kAddressWriteForms[] = {
    {.control = 'w', .min_length = 7, .max_length = 15, .fields = kAddressFields},
};

// 4.10 VOM (video output parameters)
constexpr EnumValue kFlip[] = {
    {'0', "normal"},
    {'1', "flipped"},
};
constexpr EnumValue kOnOff[] = {
    {'0', "off"},
    {'1', "on"},
};
constexpr FieldSpec kVomFields[] = {
    {.name = "h_flip", .kind = FieldKind::enum_char, .width = 1, .enums = kFlip},
    {.name = "v_flip", .kind = FieldKind::enum_char, .width = 1, .enums = kFlip},
    {.name = "fps", .kind = FieldKind::hex_u, .width = 2, .unit = "fps"},
    {.name = "gop", .kind = FieldKind::hex_u, .width = 2, .note = "frames per key frame"},
    {.name = "bitrate",
     .kind = FieldKind::hex_u,
     .width = 4,
     .unit = "kbps",
     .min = 100,
     .max = 10240,
     .note = "100k-10240k; the document's hex range [0064-0280] ends at 640"},
    {.name = "output",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kOnOff,
     .note = "video data output"},
};
constexpr FormSpec kVomForms[] = {
    {.control = 'w', .min_length = 11, .max_length = 11, .fields = kVomFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 11,
     .max_length = 11,
     .fields = kVomFields},
};

// 4.11 VER
constexpr FieldSpec kVerFields[] = {
    {.name = "version", .kind = FieldKind::text, .width = 0},
};
constexpr FormSpec kVerForms[] = {
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 1,
     .max_length = 15,
     .fields = kVerFields},
};

// 4.12 EXT (extension bits)
constexpr EnumValue kExtReserved[] = {
    {'0', "zero"},
};
constexpr EnumValue kExtCalibrate[] = {
    {'0', "off"},
    {'1', "calibrate_vignetting"},
};
constexpr FieldSpec kExtFields[] = {
    {.name = "reserved",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kExtReserved,
     .note = "x0: always 0"},
    {.name = "calibration",
     .kind = FieldKind::enum_char,
     .width = 1,
     .enums = kExtCalibrate,
     .note = "x1: 1 = calibrate the pot-lid effect"},
    {.name = "osd", .kind = FieldKind::enum_char, .width = 1, .enums = kOnOff},
    {.name = "led", .kind = FieldKind::enum_char, .width = 1, .enums = kOnOff},
};
constexpr FormSpec kExtForms[] = {
    {.control = 'w', .min_length = 4, .max_length = 4, .fields = kExtFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 4,
     .max_length = 4,
     .fields = kExtFields},
};

// 4.13 UID
constexpr FieldSpec kUidFields[] = {
    {.name = "uid", .kind = FieldKind::hex_u, .width = 8},
};
constexpr FormSpec kUidForms[] = {
    {.control = 'w', .min_length = 8, .max_length = 8, .fields = kUidFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 8,
     .max_length = 8,
     .fields = kUidFields},
};

// 4.14 TSM (thermal scene mode)
constexpr EnumValue kTsm[] = {
    {0x00, "general"},        {0x03, "low_temperature_highlight"},
    {0x04, "linear_stretch"}, {0x05, "low_contrast"},
    {0x06, "high_contrast"},  {0x07, "bright_highlight"},
};
constexpr FieldSpec kTsmFields[] = {
    {.name = "scene", .kind = FieldKind::enum_hex, .width = 2, .enums = kTsm},
};
constexpr FormSpec kTsmForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTsmFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTsmFields},
};

// 4.15 TAS (thermal auto shutter interval)
constexpr EnumValue kTasLabels[] = {
    {0x00, "auto_shutter_off"},
};
constexpr FieldSpec kTasFields[] = {
    {.name = "interval",
     .kind = FieldKind::hex_u,
     .width = 2,
     .unit = "s",
     .min = 0,
     .max = 100,
     .enums = kTasLabels,
     .note = "table 05-64 (5-100 s); C12 0-25 s, 00 = off; C13 5-64"},
};
constexpr FormSpec kTasForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTasFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTasFields},
};

// 4.16-4.21 TDI/TIB/TIC/TAR/TTR/TGM: one level 0-100 as two hex digits.
constexpr FieldSpec kTdiFields[] = {
    {.name = "detail", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 100},
};
constexpr FormSpec kTdiForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTdiFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTdiFields},
};
constexpr FieldSpec kTibFields[] = {
    {.name = "brightness", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 100},
};
constexpr FormSpec kTibForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTibFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTibFields},
};
constexpr FieldSpec kTicFields[] = {
    {.name = "contrast", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 100},
};
constexpr FormSpec kTicForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTicFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTicFields},
};
constexpr FieldSpec kTarFields[] = {
    {.name = "spatial_denoise", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 100},
};
constexpr FormSpec kTarForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTarFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTarFields},
};
constexpr FieldSpec kTtrFields[] = {
    {.name = "temporal_denoise", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 100},
};
constexpr FormSpec kTtrForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTtrFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTtrFields},
};
constexpr FieldSpec kTgmFields[] = {
    {.name = "gamma", .kind = FieldKind::hex_u, .width = 2, .min = 0, .max = 100},
};
constexpr FormSpec kTgmForms[] = {
    {.control = 'w', .min_length = 2, .max_length = 2, .fields = kTgmFields},
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 2,
     .max_length = 2,
     .fields = kTgmFields},
};

// 4.22 SLR (single laser range)
constexpr FieldSpec kSlrFields[] = {
    {.name = "distance",
     .kind = FieldKind::hex_u,
     .width = 4,
     .scale = 1,
     .unit = "dm",
     .min = 5,
     .max = 1000},
};
constexpr EnumValue kSlrTrigger[] = {
    {0x01, "measure"},
};
constexpr FieldSpec kSlrTriggerFields[] = {
    {.name = "action", .kind = FieldKind::enum_hex, .width = 2, .enums = kSlrTrigger},
};
constexpr FormSpec kSlrForms[] = {
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 4,
     .max_length = 4,
     .fields = kSlrFields},
    {.control = 'w',
     .role = Role::any,
     .min_length = 2,
     .max_length = 2,
     .fields = kSlrTriggerFields,
     .evidence = "a station used on a real C13 (vamaskylight/custom-GCS, vgcs/skydroid; its "
                 "tests/test_skydroid_protocol.py) sends the trigger #TPUD2wSLR015B before each "
                 "range read #TPUD2rSLR0055 (a C13 SDK, sadikbarun/skydroid_c13_miniSDK "
                 "skydroid.py @ d5a1ae12, reads without one)"},
};

// ---------------------------------------------------------------------------

// The field: identifiers the document does not list, each with its source
// (docs/sources/ardupilot.md).

// MOD (model name)
constexpr FieldSpec kModelFields[] = {
    {.name = "model", .kind = FieldKind::text, .width = 0, .note = "C11, C13 on real units"},
};
constexpr FormSpec kModForms[] = {
    {.control = 'r',
     .role = Role::request,
     .min_length = 2,
     .max_length = 2,
     .fields = kQueryFields},
    {.control = 'r',
     .role = Role::response,
     .min_length = 1,
     .max_length = 15,
     .fields = kModelFields,
     .evidence = "AP_Mount_SkyDroid takes the reply's data as the model name (C11, C13; PR "
                 "#34155); ArduPilot's SIM_SkyDroid answers #TPUD3rMODC118A / #TPUD3rMODC138C"},
};

constexpr CommandSpec kTable[] = {
    // 2.3.2
    {.ident = "ERE",
     .dialect = Dialect::skydroid,
     .address = 'M',
     .title = "invalid command reply",
     .section = "SkyDroid 2.3.2",
     .models = all,
     .forms = kEreForms,
     .note = "sent by the addressed device with the addresses swapped "
             "(#TPMU2wERE!!30; class M in the example, any class in "
             "practice); no support line: all five models assumed"},
    // 3 G class
    {.ident = "PTZ",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal control",
     .section = "SkyDroid 3.1",
     .models = c10 | c10pro | c12 | c20,
     .forms = kPtzForms},
    {.ident = "GSY",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal yaw speed",
     .section = "SkyDroid 3.2",
     .models = c10 | c10pro | c12 | c20,
     .forms = kSpeedForms,
     .note = "the text says 0.1 deg/s, the table 0.5 deg/s; field reports "
             "settle on 0.5 deg/s per step"},
    {.ident = "GSP",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal pitch speed",
     .section = "SkyDroid 3.2",
     .models = c10 | c10pro | c12 | c20,
     .forms = kSpeedForms,
     .note = "the text says 0.1 deg/s, the table 0.5 deg/s; field reports "
             "settle on 0.5 deg/s per step"},
    {.ident = "GSR",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal roll speed",
     .section = "SkyDroid 3.2",
     .models = c10 | c10pro | c12 | c20,
     .forms = kSpeedForms,
     .note = "roll commands struck out in V1.0.7 (not supported for now); "
             "the text says 0.1 deg/s, the table 0.5 deg/s"},
    {.ident = "GSM",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal yaw and pitch speed",
     .section = "SkyDroid 3.2",
     .models = c10 | c10pro | c12 | c20,
     .forms = kSpeedYawPitchForms,
     .note = "the text says 0.1 deg/s, the table 0.5 deg/s; field reports "
             "settle on 0.5 deg/s per step"},
    {.ident = "GAY",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal yaw angle",
     .section = "SkyDroid 3.3.1",
     .models = c10 | c10pro | c12 | c20,
     .forms = kAngleForms,
     .note = "the example #TPUG6wGAYEF073288 carries a checksum computed "
             "with the #tp header"},
    {.ident = "GAP",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal pitch angle",
     .section = "SkyDroid 3.3.1",
     .models = c10 | c10pro | c12 | c20,
     .forms = kAngleForms,
     .note = "pitch up positive; range +-90 since V1.0.7"},
    {.ident = "GAR",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal roll angle",
     .section = "SkyDroid 3.3.1",
     .models = c10 | c10pro | c12 | c20,
     .forms = kAngleForms,
     .note = "roll commands struck out in V1.0.7 (not supported for now)"},
    {.ident = "GAM",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal yaw and pitch angle",
     .section = "SkyDroid 3.3.1",
     .models = c10 | c10pro | c12 | c20,
     .forms = kAngleYawPitchForms,
     .note = "#TPUG C w GAM: #TP header with length C (G class)"},
    {.ident = "GAA",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "attitude push rate",
     .section = "SkyDroid 3.3.2.1",
     .models = c10 | c10pro | c12 | c20,
     .forms = kGaaForms,
     .note = "00 stops the GAC push; 01-64 hex is the rate, 1-100 Hz"},
    {.ident = "GAC",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "gimbal attitude",
     .section = "SkyDroid 3.3.2.2",
     .models = c10 | c10pro | c12 | c20,
     .forms = kGacForms,
     .note = "stream enabled by GAA; no read request is documented; the "
             "documented frame #TPUGCrGAC keeps U as source, so role any"},
    {.ident = "SUM",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "tracking control",
     .section = "SkyDroid 3.3.4",
     .models = c12,
     .forms = kSumForms},
    {.ident = "GOT",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "track target at position",
     .section = "SkyDroid 3.3.5",
     .models = c12,
     .forms = kGotForms,
     .note = "position in a 1280x720 frame, (0,0) top left; the example "
             "#TPUG8wGOT02800168D5 carries a checksum computed with the #tp "
             "header"},
    {.ident = "FAE",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "flight controller attitude input enable",
     .section = "SkyDroid 3.3.6.1",
     .models = c12,
     .forms = kFaeForms},
    {.ident = "FAI",
     .dialect = Dialect::skydroid,
     .address = 'G',
     .title = "flight controller attitude",
     .section = "SkyDroid 3.3.6.2",
     .models = c12,
     .forms = kFaiForms,
     .note = "sent by the flight controller; 3.3.6.2 has no support line, "
             "C12 taken from 3.3.6.1; the field: ArduPilot's SkyDroid driver adds a mode byte "
             "(14 chars)"},
    // 4 D class
    {.ident = "REC",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "recording",
     .section = "SkyDroid 4.1",
     .models = c10 | c10pro | c12,
     .forms = kRecForms},
    {.ident = "CAP",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "take photo",
     .section = "SkyDroid 4.2",
     .models = c10 | c10pro | c12,
     .forms = kCapForms,
     .note = "data 01 is the only documented value"},
    {.ident = "VID",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "recording resolution",
     .section = "SkyDroid 4.3",
     .models = c12,
     .forms = kVidForms,
     .note = "one char per lens: x0 used only with two visible-light lenses"},
    {.ident = "SDC",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "memory card capacity",
     .section = "SkyDroid 4.4",
     .models = c12,
     .forms = kSdcForms,
     .note = "response: free then total, 5 hex digits each, in MB; all zero "
             "means no card inserted"},
    {.ident = "AWB",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "white balance",
     .section = "SkyDroid 4.5.1",
     .models = all,
     .forms = kAwbForms,
     .note = "no support line: all five models assumed; the table labels "
             "both x0 and x1 as the secondary lens (x1 is the main one)"},
    {.ident = "IQE",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "image parameters",
     .section = "SkyDroid 4.5.2",
     .models = c12,
     .forms = kIqeForms,
     .note = "the example #TPUDCwIQE uses #TP with length C"},
    {.ident = "TIM",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "time",
     .section = "SkyDroid 4.6",
     .models = c10 | c10pro | c12,
     .forms = kTimForms,
     .note = "hhmmss.ss then DDMMYY (NMEA order), decimal; example "
             "142832.00031218 = 2018-12-03 14:28:32"},
    {.ident = "DZM",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "digital zoom",
     .section = "SkyDroid 4.7",
     .models = c12,
     .forms = kDzmForms},
    {.ident = "IMG",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal palette",
     .section = "SkyDroid 4.8",
     .models = c12,
     .forms = kImgForms,
     .note = "the section title reads 'camouflage' for 'pseudo-colour palette'; "
             "02 is not listed"},
    {.ident = "IPV",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "camera IP address",
     .section = "SkyDroid 4.9.1",
     .models = all,
     .forms = kAddressReadWriteForms,
     .note = "no support line: all five models assumed (2.1.1: C10 and C20 "
             "differ in transport); the documented response #tpUDDrIPV "
             "keeps U as source"},
    {.ident = "GTW",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "camera gateway",
     .section = "SkyDroid 4.9.2",
     .models = all,
     .forms = kAddressReadWriteForms,
     .note = "4.9.2.2 lists the identifier IPV for setting the gateway (erratum; the "
             "example uses GTW); no support line: all five models assumed"},
    {.ident = "DNS",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "DNS server",
     .section = "SkyDroid 4.9.2",
     .models = all,
     .forms = kAddressWriteForms,
     .note = "only the set command is documented (4.9.2 table); no support "
             "line: all five models assumed"},
    {.ident = "BNS",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "backup DNS server",
     .section = "SkyDroid 4.9.2",
     .models = all,
     .forms = kAddressWriteForms,
     .note = "only the set command is documented (4.9.2 table); no support "
             "line: all five models assumed"},
    {.ident = "VOM",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "video output parameters",
     .section = "SkyDroid 4.10",
     .models = c10 | c10pro | c12,
     .forms = kVomForms,
     .note = "the set example #tpUDBwVOM111E1E04001AE has checksum AE, the "
             "sum is 8E; bitrate hex range written [0064-0280] (0280 = 640, "
             "10240 is 2800)"},
    {.ident = "VER",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "software version",
     .section = "SkyDroid 4.11",
     .models = c10 | c10pro | c12,
     .forms = kVerForms,
     .note = "template #tpDU8rVERVX.X.X says length 8, the example "
             "#tpDU6rVERV1.0.0 has 6; a C12 answered #tpDU3rVER010502"},
    {.ident = "EXT",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "extension flags",
     .section = "SkyDroid 4.12",
     .models = c10pro | c12,
     .forms = kExtForms,
     .note = "x0 reserved 0, x1 pot-lid (vignetting) calibration, x2 OSD, "
             "x3 LED; the documented reply #tpUD4rEXT keeps U as source"},
    {.ident = "UID",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "user ID",
     .section = "SkyDroid 4.13",
     .models = c12,
     .forms = kUidForms,
     .note = "C12 in development; 8 hex digits though the range is written "
             "00000000-FFFFFF; the read example repeats the set frame"},
    {.ident = "TSM",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal scene mode",
     .section = "SkyDroid 4.14",
     .models = c13,
     .forms = kTsmForms},
    {.ident = "TAS",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal auto shutter interval",
     .section = "SkyDroid 4.15",
     .models = c12 | c13,
     .forms = kTasForms,
     .note = "ranges disagree: table 5-100 s (05-64), C12 0-25 s with 00 = "
             "auto shutter off, C13 5-64 s"},
    {.ident = "TDI",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal detail enhancement",
     .section = "SkyDroid 4.16",
     .models = c13,
     .forms = kTdiForms,
     .note = "4.16.1 gives only the table (its column labelled 'time') without "
             "control or identifier lines; layout taken from the read"},
    {.ident = "TIB",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal brightness",
     .section = "SkyDroid 4.17",
     .models = c13,
     .forms = kTibForms},
    {.ident = "TIC",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal contrast",
     .section = "SkyDroid 4.18",
     .models = c13,
     .forms = kTicForms},
    {.ident = "TAR",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal spatial noise reduction",
     .section = "SkyDroid 4.19",
     .models = c13,
     .forms = kTarForms},
    {.ident = "TTR",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal temporal noise reduction",
     .section = "SkyDroid 4.20",
     .models = c13,
     .forms = kTtrForms},
    {.ident = "TGM",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "thermal gamma",
     .section = "SkyDroid 4.21",
     .models = c13,
     .forms = kTgmForms},
    {.ident = "SLR",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "single laser ranging",
     .section = "SkyDroid 4.22",
     .models = c13,
     .forms = kSlrForms,
     .note = "0005-03E8 = 5-1000 dm (unit fixed in V1.1.5); the digits are "
             "written X0X1X3X4; the example reply #TPUD4rSLR keeps U as "
             "source and uses #TP with length 4"},
    // Appendix I only
    {.ident = "ZMC",
     .dialect = Dialect::skydroid,
     .address = 'M',
     .title = "zoom control",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed"},
    {.ident = "FCC",
     .dialect = Dialect::skydroid,
     .address = 'M',
     .title = "focus control",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed"},
    {.ident = "ZFP",
     .dialect = Dialect::skydroid,
     .address = 'M',
     .title = "set zoom and focus position",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed"},
    {.ident = "IRC",
     .dialect = Dialect::skydroid,
     .address = 'M',
     .title = "day/night switch",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed"},
    {.ident = "MNU",
     .dialect = Dialect::skydroid,
     .address = 'M',
     .title = "menu",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed; address class M assumed"},
    {.ident = "EVS",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "exposure compensation",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed; address class D assumed (ISP, as AWB)"},
    {.ident = "LAT",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "latitude",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed; address class D assumed"},
    {.ident = "ALT",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "altitude",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed; address class D assumed"},
    {.ident = "LON",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "longitude",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed; address class D assumed"},
    {.ident = "TMP",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "temperature",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed; address class D assumed"},
    {.ident = "RST",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "reset network configuration",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed; address class D assumed (network, as IPV)"},
    {.ident = "RTF",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "reboot, restore factory settings",
     .section = "SkyDroid appendix I",
     .models = all,
     .forms = kAppendixForms,
     .note = "layout not documented (appendix only); no support line: all "
             "five models assumed; address class D assumed"},
    // The field
    {.ident = "MOD",
     .dialect = Dialect::skydroid,
     .address = 'D',
     .title = "model name",
     .section = "field: ArduPilot AP_Mount_SkyDroid (PR #34155)",
     .models = c12 | c13,
     .forms = kModForms,
     .note = "read once a second until answered by ArduPilot's driver, #TPUD2rMOD0044; the "
             "reply's data is the model name; real units took from under a second to 8+ "
             "minutes to answer (the driver's header)",
     .evidence = "AP_Mount_SkyDroid.cpp sends and parses MOD (PR #34155, "
                 "https://github.com/ArduPilot/ardupilot/pull/34155, written against real "
                 "C11/C13 units); ArduPilot's SIM_SkyDroid answers it for C11 and C13"},
};

}  // namespace

std::span<const CommandSpec> skydroid_table() noexcept { return kTable; }

}  // namespace top::detail
