// Not part of the API: for the writers of this repository (topdump's JSON)
// that print a field's value exactly as the double nlohmann would print.
#pragma once

#include <cstdint>

#include "top/decode.hpp"

namespace top::detail {

// The decimal a numeric field stands for, exactly: its value is the double
// nearest to mantissa / 10^decimals, and `decimals` is the number of digits
// format_value shows. For the integer kinds (hex, decimal, little-endian)
// whose scale is a decimal fraction (1, 0.5, 0.01); false for the others and
// past 15 digits.
bool exact_decimal(const FieldValue& f, std::int64_t& mantissa, int& decimals) noexcept;

// The digits after the point format_value shows for a field of `scale`
// (0.01 -> 2, 0.5 -> 1, 1 -> 0); topdump wireshark labels fields with it.
int decimals_of(double scale) noexcept;

}  // namespace top::detail
