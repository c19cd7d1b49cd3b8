-- ---------------------------------------------------------------------------
-- The dissector. This part is the same for every catalog: it ports the
-- frame parser (protocol/src/frame.cpp), the stream decoder
-- (protocol/src/stream.cpp), the field decoder (protocol/src/decode.cpp) and
-- the dialect and role rules of topdump (analyzer/src/analyzer.cpp) to Lua,
-- reading the tables above. Keep it in step with them: ctest compares this
-- dissector with topdump on every bundled capture.

local sbyte, ssub, sfmt, schar = string.byte, string.sub, string.format, string.char

local function is_hex(c)
  return c ~= nil and ((c >= 48 and c <= 57) or (c >= 65 and c <= 70) or (c >= 97 and c <= 102))
end
local function hexv(c)
  if c == nil then return -1 end
  if c >= 48 and c <= 57 then return c - 48 end
  if c >= 65 and c <= 70 then return c - 55 end
  if c >= 97 and c <= 102 then return c - 87 end
  return -1
end
local function is_lower_hex(c) return c ~= nil and c >= 97 and c <= 102 end
local ADDR = { [85] = true, [77] = true, [68] = true, [69] = true, [80] = true, [71] = true }
local function is_address(c) return ADDR[c] == true end
local function is_ident_char(c) return c ~= nil and ((c >= 65 and c <= 90) or (c >= 48 and c <= 57)) end
local function is_boundary(c) return c == 35 or c == 13 or c == 10 end
local function hex2(v) return sfmt("%02X", v % 256) end
local function printable(c)
  if c >= 0x20 and c < 0x7F then return "'" .. schar(c) .. "'" end
  return sfmt("0x%02X", c)
end
local function byte_sum(b, from, to) -- bytes [from, to) of b, 0-based
  local s = 0
  for i = from + 1, to do s = s + sbyte(b, i) end
  return s
end

local function finding(code, offset, message, quirk, severity)
  return { code = code, severity = severity or FINDINGS[code], offset = offset,
           message = message, quirk = quirk }
end

local HEADER_TEXT = { fixed = "#TP", variable = "#tp", ext8 = "#tP", ext16 = "#Tp", tmp = "#P" }
local HEADER_VARIANTS = { "TP", "tp", "tP", "Tp" }
local MAX_DATA_HEX = 15

-- parse_frame(): the frame that starts at byte p0 (0-based) of b.
-- Returns "frame", consumed, frame | "need_more" | "invalid", 0, finding.
local function parse_frame(b, p0, at_end)
  local n = #b - p0
  local function B(i) return sbyte(b, p0 + i + 1) end
  local function truncated(have, want)
    return "invalid", 0, finding("truncated", have, "input ends after " .. have ..
                                 " bytes of a frame that needs " .. want)
  end
  local function invalid(code, offset, message) return "invalid", 0, finding(code, offset, message) end
  -- The input ends before byte `want` of the frame: wait for more, or truncated at the end.
  local function short(want)
    if at_end then return truncated(n, want) end
    return "need_more"
  end
  local function bad_control()
    return invalid("bad-control", 6, "control char " .. printable(B(6)) .. " is not r or w")
  end
  if n == 0 then return short(1) end
  if B(0) ~= 35 then return invalid("bad-header", 0, "frame must start with '#', got " .. printable(B(0))) end
  local header, control, ident_at, data_at, declared = "variable", nil, 7, 10, 0
  local hex_length, two_digit = true, false
  local notes = {}
  if n < 2 then return short(12) end
  local c1 = B(1)
  if c1 == 80 then
    local tmp = "#PDP??TMP"
    for i = 1, 8 do
      if i >= n then return short(33) end
      local k = sbyte(tmp, i + 1)
      local ok
      if k == 63 then ok = is_hex(B(i)) else ok = B(i) == k end
      if not ok then
        return invalid("bad-header", 1, "'#' followed by " .. printable(c1) ..
                       ", not a TOP header (#TP #tp #tP #Tp)")
      end
    end
    header, ident_at, data_at = "tmp", 6, 9
    declared = hexv(B(4)) * 16 + hexv(B(5))
    hex_length = false
  else
    if c1 ~= 84 and c1 ~= 116 then
      return invalid("bad-header", 1, "'#' followed by " .. printable(c1) ..
                     ", not a TOP header (#TP #tp #tP #Tp)")
    end
    if n < 3 then return short(12) end
    local c2 = B(2)
    if c2 ~= 80 and c2 ~= 112 then
      return invalid("bad-header", 2, "\"#" .. schar(c1) .. "\" followed by " .. printable(c2) ..
                     ", not a TOP header")
    end
    if c1 == 84 then
      header = c2 == 80 and "fixed" or "ext16"
    else
      header = c2 == 112 and "variable" or "ext8"
    end
  end

  if header ~= "tmp" then
    for i = 3, 4 do
      if n < i + 1 then return short(12) end
      if not is_address(B(i)) then
        return invalid("bad-address", i, (i == 3 and "source" or "destination") .. " address " ..
                       printable(B(i)) .. " is not one of U M D E P G")
      end
    end
    if n < 6 then return short(12) end
    if header == "fixed" or header == "variable" then
      if not is_hex(B(5)) then
        return invalid("bad-length-char", 5, "length char " .. printable(B(5)) .. " is not a hex digit")
      end
      if is_lower_hex(B(5)) then
        notes[#notes + 1] = finding("lowercase-hex", 5, "length char written in lowercase")
      end
      if n < 7 then return short(12) end
      if B(6) == 114 or B(6) == 119 then
        control = B(6)
        declared = hexv(B(5))
      elseif is_hex(B(6)) then
        if n < 8 then return short(13) end
        if B(7) ~= 114 and B(7) ~= 119 then
          return bad_control()
        end
        control = B(7)
        declared = hexv(B(5)) * 16 + hexv(B(6))
        two_digit, hex_length, ident_at, data_at = true, false, 8, 11
      else
        return bad_control()
      end
    elseif header == "ext8" then
      declared = B(5)
      hex_length = false
      if n < 7 then return short(12) end
      if B(6) ~= 114 and B(6) ~= 119 then
        return bad_control()
      end
      control = B(6)
    else -- ext16
      if n < 7 then return short(12) end
      declared = B(5) * 256 + B(6)
      hex_length, control, ident_at, data_at = false, nil, 7, 10
    end
  end

  for i = ident_at, ident_at + 2 do
    if n < i + 1 then return short(data_at + 2) end
    if not is_ident_char(B(i)) then
      return invalid("bad-ident", i, "identifier char " .. printable(B(i)) ..
                     " is not an uppercase letter or digit")
    end
  end

  local f = { header = header, findings = notes, terminator = 0, declared_length = declared,
              data_offset = data_at, ident_at = ident_at }
  f.src = header == "tmp" and B(2) or B(3)
  f.dst = header == "tmp" and B(3) or B(4)
  f.control = control
  f.ident = ssub(b, p0 + ident_at + 1, p0 + ident_at + 3)
  if header == "tmp" or (two_digit and f.ident == "TMP") then
    if header == "tmp" then
      notes[#notes + 1] = finding("tmp-quirk", 1, "the malformed TMP form documented in Topotek 12.2 " ..
                                  "(#PDP16TMP: no 'tp', two-digit length, no control char)",
                                  QUIRKS["tmp-quirk"])
    else
      notes[#notes + 1] = finding("tmp-quirk", 5, "TMP frame with a two-digit length (Topotek 12.2: " ..
                                  "22 data chars do not fit one hex digit)", QUIRKS["tmp-quirk"])
    end
  elseif two_digit then
    notes[#notes + 1] = finding("two-digit-length", 5, "length written as two hex digits (0x" ..
                                ssub(b, p0 + 6, p0 + 7) .. ")")
  end

  local L = declared
  local declared_cs = data_at + L
  local declared_end = declared_cs + 2
  local lookahead = data_at + MAX_DATA_HEX + 3
  if not at_end and n < declared_end then return "need_more" end

  local function checksum_at(p, prefix)
    if p + 2 > n then return false end
    local hi, lo = hexv(B(p)), hexv(B(p + 1))
    if hi < 0 or lo < 0 then return false end
    local v = hi * 16 + lo
    return v == prefix % 256, v
  end
  local function finish(data_len, present, value, prefix)
    f.data_length = data_len
    local e = data_at + data_len + (present and 2 or 0)
    f.raw = ssub(b, p0 + 1, p0 + e)
    f.expected = prefix % 256
    f.present = present
    f.checksum = value
    f.checksum_ok = present and value == f.expected
    return "frame", e, f
  end

  local prefix_declared = 0
  if n >= declared_end then
    prefix_declared = byte_sum(b, p0, p0 + declared_cs)
    local ok, v = checksum_at(declared_cs, prefix_declared)
    if ok then
      if is_lower_hex(B(declared_cs)) or is_lower_hex(B(declared_cs + 1)) then
        notes[#notes + 1] = finding("checksum-case", declared_cs, "checksum " ..
                                    ssub(b, p0 + declared_cs + 1, p0 + declared_cs + 2) ..
                                    " is right but lowercase; strict receivers expect " .. hex2(v))
      end
      return finish(L, true, v, prefix_declared)
    end
  end

  if hex_length then
    if not at_end and n < lookahead then return "need_more" end
    local found, count, found_value, found_prefix = nil, 0, 0, 0
    local s = byte_sum(b, p0, p0 + data_at)
    for dl = 0, MAX_DATA_HEX do
      local p = data_at + dl
      if dl > 0 then s = s + B(p - 1) end
      if p + 2 > n then break end
      if dl ~= L then
        local ok, v = checksum_at(p, s)
        if ok then
          local bounded = (p + 2 == n and at_end) or (p + 2 < n and is_boundary(B(p + 2)))
          if bounded then
            count = count + 1
            found, found_value, found_prefix = dl, v, s
          end
        end
      end
    end
    if count == 1 then
      notes[#notes + 1] = finding("length-mismatch", 5, "declared length " .. L ..
                                  " but the checksum validates with " .. found ..
                                  " data bytes; decoded with " .. found)
      return finish(found, true, found_value, found_prefix)
    end
  end

  if n < declared_end then
    if n == declared_cs then
      local p = byte_sum(b, p0, p0 + declared_cs)
      notes[#notes + 1] = finding("no-checksum", declared_cs,
                                  "frame ends where its checksum should be (expected " .. hex2(p) .. ")")
      return finish(L, false, 0, p)
    end
    return truncated(n, declared_end)
  end

  if is_boundary(B(declared_cs)) then
    notes[#notes + 1] = finding("no-checksum", declared_cs,
                                "frame ends where its checksum should be (expected " ..
                                hex2(prefix_declared) .. ")")
    return finish(L, false, 0, prefix_declared)
  end

  local expected = prefix_declared % 256
  local got = ssub(b, p0 + declared_cs + 1, p0 + declared_cs + 2)
  local hi, lo = hexv(B(declared_cs)), hexv(B(declared_cs + 1))
  local present = hi >= 0 and lo >= 0
  local value = present and (hi * 16 + lo) or 0
  if present and header ~= "tmp" then
    local base = prefix_declared - B(1) - B(2)
    local own = ssub(b, p0 + 2, p0 + 3)
    for _, v in ipairs(HEADER_VARIANTS) do
      if v ~= own and (base + sbyte(v, 1) + sbyte(v, 2)) % 256 == value then
        notes[#notes + 1] = finding("checksum-header-case", declared_cs, "checksum " .. got ..
                                    " is the sum with header #" .. v .. ", not #" .. own ..
                                    " (expected " .. hex2(expected) .. ")",
                                    QUIRKS["checksum-header-case"])
        return finish(L, true, value, prefix_declared)
      end
    end
  end
  if present then
    notes[#notes + 1] = finding("bad-checksum", declared_cs, "checksum " .. got .. ", expected " ..
                                hex2(expected))
  else
    notes[#notes + 1] = finding("bad-checksum", declared_cs, "checksum field '" .. got ..
                                "' is not two hex digits, expected " .. hex2(expected))
  end
  return finish(L, present, value, prefix_declared)
end

