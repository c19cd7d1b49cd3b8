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
  if n == 0 then
    if at_end then return truncated(0, 1) end
    return "need_more"
  end
  if B(0) ~= 35 then return invalid("bad-header", 0, "frame must start with '#', got " .. printable(B(0))) end
  local header, control, ident_at, data_at, declared = "variable", nil, 7, 10, 0
  local hex_length, two_digit = true, false
  local notes = {}
  if n < 2 then
    if at_end then return truncated(n, 12) end
    return "need_more"
  end
  local c1 = B(1)
  if c1 == 80 then
    local tmp = "#PDP??TMP"
    for i = 1, 8 do
      if i >= n then
        if at_end then return truncated(n, 33) end
        return "need_more"
      end
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
    if n < 3 then
      if at_end then return truncated(n, 12) end
      return "need_more"
    end
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
      if n < i + 1 then
        if at_end then return truncated(n, 12) end
        return "need_more"
      end
      if not is_address(B(i)) then
        return invalid("bad-address", i, (i == 3 and "source" or "destination") .. " address " ..
                       printable(B(i)) .. " is not one of U M D E P G")
      end
    end
    if n < 6 then
      if at_end then return truncated(n, 12) end
      return "need_more"
    end
    if header == "fixed" or header == "variable" then
      if not is_hex(B(5)) then
        return invalid("bad-length-char", 5, "length char " .. printable(B(5)) .. " is not a hex digit")
      end
      if is_lower_hex(B(5)) then
        notes[#notes + 1] = finding("lowercase-hex", 5, "length char written in lowercase")
      end
      if n < 7 then
        if at_end then return truncated(n, 12) end
        return "need_more"
      end
      if B(6) == 114 or B(6) == 119 then
        control = B(6)
        declared = hexv(B(5))
      elseif is_hex(B(6)) then
        if n < 8 then
          if at_end then return truncated(n, 13) end
          return "need_more"
        end
        if B(7) ~= 114 and B(7) ~= 119 then
          return invalid("bad-control", 6, "control char " .. printable(B(6)) .. " is not r or w")
        end
        control = B(7)
        declared = hexv(B(5)) * 16 + hexv(B(6))
        two_digit, hex_length, ident_at, data_at = true, false, 8, 11
      else
        return invalid("bad-control", 6, "control char " .. printable(B(6)) .. " is not r or w")
      end
    elseif header == "ext8" then
      declared = B(5)
      hex_length = false
      if n < 7 then
        if at_end then return truncated(n, 12) end
        return "need_more"
      end
      if B(6) ~= 114 and B(6) ~= 119 then
        return invalid("bad-control", 6, "control char " .. printable(B(6)) .. " is not r or w")
      end
      control = B(6)
    else -- ext16
      if n < 7 then
        if at_end then return truncated(n, 12) end
        return "need_more"
      end
      declared = B(5) * 256 + B(6)
      hex_length, control, ident_at, data_at = false, nil, 7, 10
    end
  end

  for i = ident_at, ident_at + 2 do
    if n < i + 1 then
      if at_end then return truncated(n, data_at + 2) end
      return "need_more"
    end
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
                                  "topotek-tmp-length")
    else
      notes[#notes + 1] = finding("tmp-quirk", 5, "TMP frame with a two-digit length (Topotek 12.2: " ..
                                  "22 data chars do not fit one hex digit)", "topotek-tmp-length")
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
                                    " (expected " .. hex2(expected) .. ")", "skydroid-doc-header-case")
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

-- The stream decoder's pump over the bytes b: items in order, and where the
-- bytes not yet decided start (at_end: all are decided).
local MAX_INNER = 16
local function decode_bytes(b, at_end)
  local items, pos, n = {}, 0, #b
  local pending = nil
  local function release()
    if pending then
      if pending.frame.terminator > 0 then
        local f = pending.frame
        f.findings[#f.findings + 1] = finding("crlf", #f.raw, "frame followed by " .. f.terminator ..
                                              " CR/LF byte(s)")
      end
      items[#items + 1] = pending
      pending = nil
    end
  end
  local function garbage(at, len, why)
    release()
    local last = items[#items]
    if last and last.kind == "garbage" and last.offset + last.length == at then
      last.length = last.length + len
      return
    end
    items[#items + 1] = { kind = "garbage", offset = at, length = len,
                          finding = why or finding("garbage", 0, len .. " byte(s) outside any frame") }
  end
  while pos < n do
    local c = sbyte(b, pos + 1)
    if pending and (c == 13 or c == 10) then
      pending.frame.terminator = pending.frame.terminator + 1
      pos = pos + 1
    elseif c ~= 35 then
      release()
      local nx = string.find(b, "#", pos + 1, true)
      local e = nx and (nx - 1) or n
      garbage(pos, e - pos, nil)
      pos = e
    else
      release()
      local st, consumed, r = parse_frame(b, pos, at_end)
      if st == "need_more" then break end
      if st == "invalid" and not at_end and r.code == "truncated" then break end
      if st == "invalid" then
        local nx = string.find(b, "#", pos + 2, true)
        local e = nx and (nx - 1) or n
        garbage(pos, e - pos, r)
        pos = e
      else
        local wait, yielded = false, false
        if not r.checksum_ok then
          local tried = 0
          for q = pos + 1, pos + consumed - 1 do
            if tried >= MAX_INNER then break end
            if sbyte(b, q + 1) == 35 then
              local ist, _, inner = parse_frame(b, q, at_end)
              if ist == "need_more" then
                wait = true
                break
              end
              tried = tried + 1
              if ist == "frame" and inner.checksum_ok then
                local code = "bad-checksum"
                for _, x in ipairs(r.findings) do
                  if x.code == "no-checksum" then code = "no-checksum" end
                end
                garbage(pos, q - pos, finding(code, 0, "abandoned a frame that fails its checksum " ..
                                              "for a valid frame at +" .. (q - pos)))
                pos = q
                yielded = true
                break
              end
            end
          end
        end
        if wait then break end
        if not yielded then
          pending = { kind = "frame", offset = pos, length = consumed, frame = r }
          pos = pos + consumed
        end
      end
    end
  end
  release()
  return items, pos
end

-- --- decoding ----------------------------------------------------------------

local function dialect_from_frame(f)
  if f.src == 80 or f.dst == 80 then return "topotek" end
  if f.header == "ext8" or f.header == "ext16" or f.header == "tmp" then return "topotek" end
  local sky, topo = CATALOG.skydroid[f.ident] ~= nil, CATALOG.topotek[f.ident] ~= nil
  if sky and not topo then return "skydroid" end
  if topo and not sky then return "topotek" end
  return "unknown"
end

local function role_from_addresses(f)
  local from_client = f.src == 85 or f.src == 80
  local to_client = f.dst == 85 or f.dst == 80
  if from_client and not to_client then return "request" end
  if to_client and not from_client then return "response" end
  return "any"
end

local function fmt_number(v, d) return sfmt("%." .. d .. "f", v) end

local function all_printable(s)
  return not string.find(s, "[^\32-\126]")
end

-- "[-+]digits[.digits]" as a number, or nil.
local function parse_number(s)
  if not string.find(s, "^[-+]?%d*%.?%d*$") or not string.find(s, "%d") then return nil end
  local neg = ssub(s, 1, 1) == "-"
  local t = s
  if neg or ssub(s, 1, 1) == "+" then t = ssub(s, 2) end
  local ip, fp = string.match(t, "^(%d*)%.?(%d*)$")
  local v = 0
  for i = 1, #ip do v = v * 10 + (sbyte(ip, i) - 48) end
  local frac = 0.1
  for i = 1, #fp do
    v = v + (sbyte(fp, i) - 48) * frac
    frac = frac / 10
  end
  return neg and -v or v
end

local function scaled(iv, spec)
  if spec.mul then
    if spec.dec == 0 then return iv * spec.mul end
    return (iv * spec.mul) / (10 ^ spec.dec)
  end
  return iv * spec.scale
end

local function judge(ctx, spec, bytes, offset, fv)
  if spec.enums then
    local name = spec.enums[fv.integer]
    if name then
      fv.enum_name = name
      return
    end
    if spec.kind == "enum_hex" or spec.kind == "enum_char" then
      ctx.add("value-out-of-range", offset, spec.name .. ": '" .. bytes .. "' is not a documented value")
      return
    end
  end
  if spec.min == nil then return end
  local v = fv.value
  if v < spec.min - 1e-9 or v > spec.max + 1e-9 then
    local d = spec.dec or 0
    ctx.add("value-out-of-range", offset, spec.name .. " " .. fmt_number(v, d) ..
            (spec.unit ~= "" and " " or "") .. spec.unit .. " outside [" .. fmt_number(spec.min, d) ..
            ", " .. fmt_number(spec.max, d) .. "]")
  end
end

local function decode_field(ctx, spec, bytes, offset)
  local fv = { spec = spec, offset = offset, length = #bytes, valid = false, none = false,
               integer = 0, value = 0, text = bytes }
  if spec.none and bytes == spec.none then
    fv.none, fv.valid = true, true
    return fv
  end
  local function bad(why)
    ctx.add("bad-field", offset, spec.name .. ": " .. why)
    return fv
  end
  local k = spec.kind
  if k == "hex_u" or k == "hex_s" or k == "enum_hex" then
    if #bytes == 0 or #bytes > 15 then return bad("no hex digits") end
    if string.find(bytes, "[^0-9A-Fa-f]") then return bad("'" .. bytes .. "' is not hex") end
    if string.find(bytes, "[a-f]") and not ctx.lowercase_reported then
      ctx.lowercase_reported = true
      ctx.add("lowercase-hex", offset, spec.name .. ": hex digits '" .. bytes .. "' in lowercase")
    end
    local v = tonumber(bytes, 16)
    if k == "hex_s" then
      local bits = #bytes * 4
      if v >= 2 ^ (bits - 1) then v = v - 2 ^ bits end
    end
    fv.integer = v
    fv.value = scaled(v, spec)
    fv.valid = true
  elseif k == "dec_u" then
    if #bytes == 0 then return bad("no digits") end
    if string.find(bytes, "[^0-9]") then return bad("'" .. bytes .. "' is not decimal") end
    local v = tonumber(bytes, 10)
    fv.integer = v
    fv.value = scaled(v, spec)
    fv.valid = true
  elseif k == "enum_char" then
    if #bytes == 0 then return bad("empty") end
    fv.integer = sbyte(bytes, 1)
    fv.value = fv.integer
    fv.valid = true
  elseif k == "text" then
    if not all_printable(bytes) then return bad("non-printable bytes in text") end
    fv.valid = true
    return fv
  elseif k == "number" then
    local t = string.match(bytes, "^ *(.-)$")
    local v = parse_number(t)
    if v == nil then return bad("'" .. bytes .. "' is not a number") end
    fv.value = v * spec.scale
    fv.integer = v >= 0 and math.floor(v) or math.ceil(v)
    fv.valid = true
  elseif k == "le_i16" or k == "le_u16" or k == "le_i32" then
    local w = k == "le_i32" and 4 or 2
    if #bytes ~= w then return bad("needs " .. w .. " bytes") end
    local u = 0
    for i = w, 1, -1 do u = u * 256 + sbyte(bytes, i) end
    if k == "le_i16" and u >= 32768 then u = u - 65536 end
    if k == "le_i32" and u >= 2147483648 then u = u - 4294967296 end
    fv.integer = u
    fv.value = scaled(u, spec)
    fv.valid = true
  elseif k == "nmea" then
    if #bytes < 2 then return bad("too short for a hemisphere and a coordinate") end
    local hemi = ssub(bytes, 1, 1)
    if hemi ~= "E" and hemi ~= "W" and hemi ~= "N" and hemi ~= "S" then
      return bad("hemisphere '" .. hemi .. "' is not N S E W")
    end
    local raw = parse_number(ssub(bytes, 2))
    if raw == nil or raw < 0 then return bad("'" .. ssub(bytes, 2) .. "' is not dddmm.mmmm") end
    local deg = math.floor(raw / 100.0)
    local v = deg + (raw - deg * 100.0) / 60.0
    if hemi == "W" or hemi == "S" then v = -v end
    fv.value = v
    fv.valid = true
  else -- raw
    fv.valid = true
    return fv
  end
  judge(ctx, spec, bytes, offset, fv)
  return fv
end

-- The value as a person reads it (decode.cpp append_value).
local function format_value(fv)
  local s = fv.spec
  if fv.none then return "none (" .. fv.text .. ")" end
  if not fv.valid then return "'" .. fv.text .. "' (invalid)" end
  local unit = s.unit ~= "" and (" " .. s.unit) or ""
  local k = s.kind
  if k == "enum_hex" or k == "enum_char" then
    local code = fv.text
    if k == "enum_hex" then code = sfmt("%0" .. fv.length .. "X", fv.integer) end
    if fv.enum_name then return fv.enum_name .. " (" .. code .. ")" end
    return code .. " (undocumented)"
  elseif k == "text" or k == "raw" then
    return fv.text
  elseif k == "nmea" then
    return fmt_number(fv.value, 7) .. unit .. " (" .. fv.text .. ")"
  elseif k == "number" then
    return fv.text .. unit
  end
  local t = fmt_number(fv.value, s.dec or 0) .. unit
  if fv.enum_name then t = t .. " (" .. fv.enum_name .. ")" end
  return t
end

local function role_fits(form, frame) return form == "any" or frame == "any" or form == frame end

local function decode(f, dialect, role, model)
  local out = { dialect = dialect, role = role, findings = {}, fields = {} }
  local ctx = { lowercase_reported = false }
  function ctx.add(code, offset, message)
    out.findings[#out.findings + 1] = finding(code, offset, message)
  end
  local d = dialect
  if d == "unknown" then d = dialect_from_frame(f) end
  local ident = f.ident
  local ident_at = f.header == "tmp" and 6 or f.data_offset - 3
  local cmd
  if d == "unknown" then
    cmd = CATALOG.skydroid[ident] or CATALOG.topotek[ident]
  else
    cmd = CATALOG[d][ident]
  end
  if cmd and d == "unknown" then d = cmd.dialect end
  out.dialect = d
  out.command = cmd
  if f.header == "fixed" and f.declared_length ~= 2 then
    local g = cmd ~= nil and cmd.address == "G" and d == "skydroid"
    out.findings[#out.findings + 1] = finding("tp-length", 5, "#TP frame with length " ..
                                              f.declared_length .. " (the fixed header implies 2)" ..
                                              (g and "; SkyDroid puts every G-class command under #TP" or ""),
                                              nil, g and "info" or nil)
  end
  if d == "skydroid" and (f.header == "ext8" or f.header == "ext16") then
    ctx.add("ext-header-dialect", 0, HEADER_TEXT[f.header] ..
            " is a Topotek extended header; SkyDroid defines only #TP/#tp")
  end
  if not cmd then
    ctx.add("unknown-ident", ident_at, "identifier " .. ident .. " is not in the " ..
            (d == "unknown" and "TOP" or d) .. " catalog")
    return out
  end
  if model ~= "auto" and not cmd.models[model] then
    ctx.add("unsupported-on-model", ident_at, ident .. " (" .. cmd.section .. ") is not listed for " .. model)
  end
  if ident == "ERE" then
    ctx.add("error-reply", ident_at, "the device rejected a command as invalid (" .. schar(f.src) ..
            " to " .. schar(f.dst) .. ")")
  end
  local len = f.data_length
  local ctl = f.control and schar(f.control) or nil
  local form, swapped, control_known = nil, false, false
  for _, fm in ipairs(cmd.forms) do
    if ctl == nil or fm.control == ctl then
      control_known = true
      if len >= fm.min_length and len <= fm.max_length then
        if role_fits(fm.role, out.role) then
          form = fm
          break
        end
        if not swapped and not form then swapped = true end
      end
    end
  end
  if not form and swapped then
    for _, fm in ipairs(cmd.forms) do
      if (ctl == nil or fm.control == ctl) and len >= fm.min_length and len <= fm.max_length then
        form = fm
        break
      end
    end
    if form then
      ctx.add("unswapped-addresses", 3, "laid out as a " .. (form.role == "response" and "response" or "request") ..
              " but addressed " .. schar(f.src) .. " to " .. schar(f.dst))
    end
  end
  if not control_known then
    ctx.add("unsupported-control", 6, ident .. " has no '" .. (ctl or "") .. "' form in " .. cmd.section)
    return out
  end
  if not form then
    local allowed = {}
    for _, fm in ipairs(cmd.forms) do
      if ctl == nil or fm.control == ctl then
        allowed[#allowed + 1] = fm.min_length == fm.max_length and tostring(fm.min_length) or
                                (fm.min_length .. "-" .. fm.max_length)
      end
    end
    ctx.add("data-length", f.data_offset, len .. " data byte(s); " .. ident .. " '" .. (ctl or "?") ..
            "' takes " .. table.concat(allowed, ", "))
    return out
  end
  out.form = form
  if form.role ~= "any" and out.role == "any" then out.role = form.role end

  local data = ssub(f.raw, f.data_offset + 1, f.data_offset + f.data_length)
  local pos = 0
  if form.none and data == form.none then
    for _, fs in ipairs(form.fields) do
      local w = fs.width ~= 0 and fs.width or (#data - pos)
      out.fields[#out.fields + 1] = { spec = fs, offset = f.data_offset + pos, length = w, valid = true,
                                      none = true, text = ssub(data, pos + 1, pos + w) }
      pos = pos + w
    end
    return out
  end
  for _, fs in ipairs(form.fields) do
    if pos >= #data and fs.width ~= 0 then break end
    local w = fs.width == 0 and (#data - pos) or fs.width
    if pos + w > #data then
      ctx.add("data-length", f.data_offset + pos, fs.name .. " needs " .. w .. " byte(s), " ..
              (#data - pos) .. " left")
      break
    end
    out.fields[#out.fields + 1] = decode_field(ctx, fs, ssub(data, pos + 1, pos + w), f.data_offset + pos)
    pos = pos + w
  end
  return out
end

local function summary(dec)
  local form = dec.form
  if form and form.none and #dec.fields > 0 and dec.fields[1].none and form.note ~= "" then
    return "none (" .. form.note .. ")"
  end
  local parts = {}
  for _, fv in ipairs(dec.fields) do parts[#parts + 1] = fv.spec.name .. " " .. format_value(fv) end
  return table.concat(parts, ", ")
end

-- --- fields --------------------------------------------------------------------

local ROLE_NAMES = { request = "request", response = "response", any = "any" }
local HF = {
  header = ProtoField.string("top.header", "Header", base.ASCII, "#TP #tp #tP #Tp, or #P (malformed TMP form)"),
  src = ProtoField.string("top.src", "Source", base.ASCII, "source address: U M D E P G"),
  dst = ProtoField.string("top.dst", "Destination", base.ASCII, "destination address: U M D E P G"),
  length = ProtoField.uint16("top.length", "Length", base.DEC, nil, nil, "data length the length field declares"),
  data_length = ProtoField.uint16("top.data_length", "Data length", base.DEC, nil, nil,
                                  "data length used to decode (differs when the length lies)"),
  control = ProtoField.string("top.control", "Control", base.ASCII, "r query, w set/control"),
  ident = ProtoField.string("top.ident", "Identifier", base.ASCII),
  title = ProtoField.string("top.title", "Command", base.ASCII, "the catalog's title of the identifier"),
  data = ProtoField.string("top.data", "Data", base.ASCII),
  checksum = ProtoField.string("top.checksum", "Checksum", base.ASCII, "checksum digits as sent"),
  checksum_expected = ProtoField.uint8("top.checksum.expected", "Expected checksum", base.HEX, nil, nil,
                                       "the sum of the bytes before the checksum, modulo 256"),
  checksum_status = ProtoField.uint8("top.checksum.status", "Checksum status", base.DEC,
                                     { [0] = "Bad", [1] = "Good", [2] = "Unverified", [3] = "Not present" }),
  role = ProtoField.string("top.role", "Role", base.ASCII, "request, response or any"),
  dialect = ProtoField.string("top.dialect", "Dialect", base.ASCII, "skydroid, topotek or unknown"),
  summary = ProtoField.string("top.summary", "Summary", base.ASCII, "topdump's one-line summary"),
  garbage = ProtoField.bytes("top.garbage", "Bytes outside any frame"),
}
do
  local all = {}
  for _, v in pairs(HF) do all[#all + 1] = v end
  for _, v in pairs(CATALOG_FIELDS) do all[#all + 1] = v end
  top.fields = all
  local experts = {}
  for _, bysev in pairs(EXPERTS) do
    for _, e in pairs(bysev) do experts[#experts + 1] = e end
  end
  top.experts = experts
end

local MODEL_PREF = { { 1, "auto", 1 } }
for i, m in ipairs(MODELS) do MODEL_PREF[#MODEL_PREF + 1] = { i + 1, m, i + 1 } end
top.prefs.dialect = Pref.enum("Dialect", 1, "auto, skydroid or topotek (forces every conversation, " ..
                              "like topdump --dialect)",
                              { { 1, "auto", 1 }, { 2, "skydroid", 2 }, { 3, "topotek", 3 } }, false)
top.prefs.model = Pref.enum("Model", 1, "the device model, for unsupported-on-model (topdump --model)",
                            MODEL_PREF, false)
top.prefs.heuristic = Pref.bool("Heuristic on any UDP/TCP port", true,
                                "claim UDP and TCP payloads that start with a valid TOP frame")

local function pref_dialect()
  local v = top.prefs.dialect
  if v == 2 then return "skydroid" elseif v == 3 then return "topotek" end
  return "unknown"
end
local function pref_model()
  local v = top.prefs.model
  if v and v >= 2 then return MODELS[v - 1] end
  return "auto"
end

-- --- conversations: dialect votes and pending requests (analyzer.cpp) ----------

local convs = {}  -- key -> conversation state (first pass)
local seen = {}   -- pinfo.number -> { [index] = { dialect, role } }
local TIMEOUT = 2.0
local MAX_PENDING = 256

function top.init()
  convs = {}
  seen = {}
end

local function endpoint(addr, port) return tostring(addr) .. ":" .. tostring(port) end

local function conversation(pinfo, transport)
  local a = endpoint(pinfo.src, pinfo.src_port)
  local b = endpoint(pinfo.dst, pinfo.dst_port)
  local key = transport .. " " .. (a < b and (a .. " " .. b) or (b .. " " .. a))
  local c = convs[key]
  if not c then
    c = { first = a, votes = { skydroid = 0, topotek = 0 }, observed = 0, port = "unknown", pending = {} }
    if transport ~= "serial" then
      local d1 = PORT_DIALECT[pinfo.src_port]
      if d1 then c.port = d1 end
      local d2 = PORT_DIALECT[pinfo.dst_port]
      if d2 then c.port = d2 end
    end
    convs[key] = c
  end
  return c, (a == c.first) and 0 or 1
end

local function current_dialect(c)
  local forced = pref_dialect()
  if forced ~= "unknown" then return forced end
  local model = pref_model()
  if model ~= "auto" then return MODEL_DIALECT[model] end
  if c.votes.skydroid > c.votes.topotek then return "skydroid" end
  if c.votes.topotek > c.votes.skydroid then return "topotek" end
  return c.port
end

local function expire(c, ts)
  while #c.pending > 0 and ts - c.pending[1].ts > TIMEOUT do table.remove(c.pending, 1) end
end

-- The dialect and role topdump gives this frame, updating the conversation.
local function judge_frame(c, dir, f, ts)
  if c.observed < 64 then
    local v = dialect_from_frame(f)
    if v ~= "unknown" then c.votes[v] = c.votes[v] + 1 end
    c.observed = c.observed + 1
  end
  local dialect = current_dialect(c)
  if dialect == "unknown" then dialect = dialect_from_frame(f) end
  local role = "any"
  local from_client = f.src == 85 or f.src == 80
  local to_client = f.dst == 85 or f.dst == 80
  if from_client and not to_client then
    for _, p in ipairs(c.pending) do
      if p.dir ~= dir and p.ident == f.ident and p.src == f.src and p.dst == f.dst then
        role = "response"
        break
      end
    end
  end
  return dialect, role
end

local function after_decode(c, dir, f, dec, ts)
  expire(c, ts)
  local data = ssub(f.raw, f.data_offset + 1, f.data_offset + f.data_length)
  if dec.role == "request" then
    if #c.pending >= MAX_PENDING then table.remove(c.pending, 1) end
    c.pending[#c.pending + 1] = { ident = f.ident, dir = dir, src = f.src, dst = f.dst, data = data, ts = ts }
  elseif dec.role == "response" then
    local ere = f.ident == "ERE"
    local pick, newest = nil, nil
    for i = #c.pending, 1, -1 do
      local p = c.pending[i]
      if p.dir ~= dir then
        if ere then
          if p.dst == f.src then
            pick = i
            break
          end
        elseif p.ident == f.ident then
          if not newest then newest = i end
          if p.data == data then
            pick = i
            break
          end
        end
      end
    end
    pick = pick or newest
    if pick then table.remove(c.pending, pick) end
  end
end

-- --- the tree ----------------------------------------------------------------------

local SEVERITY_RANK = { info = 0, warning = 1, error = 2 }

local function add_finding(item, tvb, base_off, x)
  local e = EXPERTS[x.code] and EXPERTS[x.code][x.severity]
  if not e then return end
  local msg = x.code .. ": " .. x.message
  if x.quirk then msg = msg .. " (quirk " .. x.quirk .. ")" end
  local at = base_off + x.offset
  if at >= tvb:len() then at = tvb:len() - 1 end
  if at < 0 then at = 0 end
  item:add_tvb_expert_info(e, tvb(at, 1), msg)
end

local function add_field(sub, tvb, base_off, fv)
  local s = fv.spec
  local label = s.name .. ": " .. format_value(fv)
  local r = tvb(base_off + fv.offset, fv.length)
  local pf = CATALOG_FIELDS[s.abbrev]
  if fv.none or not fv.valid or not pf then
    sub:add(r, label)
    return
  end
  local k = s.kind
  local v = fv.value
  if CATALOG_VTYPE[s.abbrev] == "string" then
    if k == "text" or k == "raw" then v = fv.text else v = format_value(fv) end
  end
  sub:add(pf, r, v, label)
end

local function letter(c) return c and schar(c) or "" end

-- Adds one TOP frame at tvb offset `off` to the tree; returns the Info text.
local function add_frame(tvb, pk, tree, off, item, c, dir, index)
  local f = item.frame
  local memo = pk.memo
  local dialect, role
  if not pk.visited and not memo[index] then
    dialect, role = judge_frame(c, dir, f, pk.ts)
    memo[index] = { dialect, role }
  elseif memo[index] then
    dialect, role = memo[index][1], memo[index][2]
  else
    dialect = pref_dialect()
    if dialect == "unknown" then dialect = dialect_from_frame(f) end
    role = "any"
  end
  local dec = decode(f, dialect, role == "any" and role_from_addresses(f) or role, pk.model)
  if role == "response" and role_from_addresses(f) == "request" then
    local has = false
    for _, x in ipairs(dec.findings) do has = has or x.code == "unswapped-addresses" end
    if not has then
      dec.findings[#dec.findings + 1] = finding("unswapped-addresses", 3, "a response addressed " ..
                                                schar(f.src) .. " to " .. schar(f.dst) ..
                                                " (the request's order; some simulators)")
    end
  end
  if not pk.visited then after_decode(c, dir, f, dec, pk.ts) end

  local total = item.length
  local t = tree:add(top, tvb(off, total))
  local sum = summary(dec)
  local info = f.ident .. (dec.role ~= "any" and (" " .. dec.role) or "") .. (sum ~= "" and (": " .. sum) or "")
  t:append_text(", " .. info)
  local hl = f.header == "tmp" and 2 or 3
  t:add(HF.header, tvb(off, hl))
  if f.header == "tmp" then
    t:add(HF.src, tvb(off + 2, 1))
    t:add(HF.dst, tvb(off + 3, 1))
    t:add(HF.length, tvb(off + 4, 2), f.declared_length)
  else
    t:add(HF.src, tvb(off + 3, 1))
    t:add(HF.dst, tvb(off + 4, 1))
    local ll = (f.header == "ext16" or f.data_offset == 11) and 2 or 1
    t:add(HF.length, tvb(off + 5, ll), f.declared_length)
    if f.control then t:add(HF.control, tvb(off + f.ident_at - 1, 1)) end
  end
  t:add(HF.data_length, tvb(off + f.data_offset, f.data_length), f.data_length)
  t:add(HF.ident, tvb(off + f.ident_at, 3))
  if dec.command then t:add(HF.title, tvb(off + f.ident_at, 3), dec.command.title) end
  if f.data_length > 0 then t:add(HF.data, tvb(off + f.data_offset, f.data_length)) end
  local cs_at = off + f.data_offset + f.data_length
  local status
  if f.present then
    local ci = t:add(HF.checksum, tvb(cs_at, 2))
    status = f.checksum_ok and 1 or 0
    ci:append_text(f.checksum_ok and " [correct]" or (" [incorrect, should be " .. hex2(f.expected) .. "]"))
    t:add(HF.checksum_expected, tvb(cs_at, 2), f.expected)
    t:add(HF.checksum_status, tvb(cs_at, 2), status)
  else
    t:add(HF.checksum_expected, tvb(cs_at - 1, 1), f.expected)
    t:add(HF.checksum_status, tvb(cs_at - 1, 1), 3)
  end
  local whole = tvb(off, total)
  t:add(HF.role, whole, dec.role)
  t:add(HF.dialect, whole, dec.dialect)
  if sum ~= "" then t:add(HF.summary, tvb(off + f.data_offset, f.data_length), sum) end
  if #dec.fields > 0 then
    local sub = t:add(tvb(off + f.data_offset, f.data_length),
                      f.ident .. (dec.command and (" (" .. dec.command.title .. ")") or ""))
    for _, fv in ipairs(dec.fields) do add_field(sub, tvb, off, fv) end
  end
  for _, x in ipairs(f.findings) do add_finding(t, tvb, off, x) end
  for _, x in ipairs(dec.findings) do add_finding(t, tvb, off, x) end
  return info
end

local function add_garbage(tvb, tree, off, item)
  local len = item.length
  if len <= 0 then return end
  local t = tree:add(top, tvb(off, len))
  t:append_text(", " .. len .. " byte(s) outside any frame")
  local g = t:add(HF.garbage, tvb(off, len))
  add_finding(g, tvb, off, item.finding)
end

-- TCP: where the bytes of tvb sit in the direction's stream. Wireshark may
-- hand a reassembled PDU over again from its start after a frame of it was
-- shown (a frame that waits for look-ahead, then one cut by the segment's
-- end); such a frame is not shown twice.
local tcp_seq = Field.new("tcp.seq")
local tcp_len = Field.new("tcp.len")
local function last_value(field)
  local all = { field() }
  local x = all[#all]
  return x and x.value
end

-- Dissects the bytes of tvb; at_end: a whole datagram or serial record.
local function dissect(tvb, pinfo, tree, transport, at_end)
  local len = tvb:len()
  if len == 0 then return 0 end
  local b = tvb:raw(0, len)
  local start = 0
  if transport == "tcp" then
    -- CR/LF left over from the frame that ended the previous PDU
    while start < len and (sbyte(b, start + 1) == 13 or sbyte(b, start + 1) == 10) do start = start + 1 end
    if start > 0 then b = ssub(b, start + 1) end
  end
  local items, upto = decode_bytes(b, at_end)
  if transport == "tcp" and upto < #b then
    pinfo.desegment_offset = start + upto
    pinfo.desegment_len = DESEGMENT_ONE_MORE_SEGMENT
  end
  if #items == 0 then
    if transport == "tcp" and upto < #b then return len end
    return 0
  end
  pinfo.cols.protocol = "TOP"
  local c, dir = conversation(pinfo, transport)
  local base = nil
  if transport == "tcp" then
    local seq, seglen = last_value(tcp_seq), last_value(tcp_len)
    if seq and seglen then base = seq + seglen - len end
  end
  local number, visited = pinfo.number, pinfo.visited
  local memo = seen[number] or {}
  seen[number] = memo
  memo.shown = memo.shown or {}
  local pk = { memo = memo, visited = visited, ts = pinfo.abs_ts, model = pref_model() }
  local infos = {}
  local index = 0
  for _, it in ipairs(items) do
    local at = base and (base + start + it.offset)
    local show
    if visited and memo.shown[start + it.offset] ~= nil then
      show = memo.shown[start + it.offset]
    else
      show = true
      if at then
        -- the same bytes at the same stream offset as one of the last frames
        -- shown in this direction (an offset alone would not do: with
        -- out-of-order segments the PDU may not end where this segment does)
        c.recent = c.recent or {}
        local r = c.recent[dir] or { keys = {}, set = {} }
        c.recent[dir] = r
        local key = at .. ":" .. (it.frame and it.frame.raw or it.length)
        if r.set[key] then
          show = false
        else
          r.set[key] = true
          r.keys[#r.keys + 1] = key
          if #r.keys > 64 then r.set[table.remove(r.keys, 1)] = nil end
        end
      end
      memo.shown[start + it.offset] = show
    end
    if show and it.kind == "frame" then
      infos[#infos + 1] = add_frame(tvb, pk, tree, start + it.offset, it, c, dir, index)
      index = index + 1
    elseif show then
      add_garbage(tvb, tree, start + it.offset, it)
    end
  end
  if #infos > 0 then pinfo.cols.info:set(table.concat(infos, " ; ")) end
  return len
end

local function transport_of(pinfo)
  local pt = pinfo.port_type
  if pt == 2 then return "tcp" end
  if pt == 3 then return "udp" end
  return "serial"
end

function top.dissector(tvb, pinfo, tree)
  local t = transport_of(pinfo)
  return dissect(tvb, pinfo, tree, t, t ~= "tcp")
end

-- The heuristic: a payload that starts with a TOP frame whose checksum holds.
local function heuristic(tvb, pinfo, tree)
  if not top.prefs.heuristic then return false end
  local len = tvb:len()
  if len < 12 or tvb(0, 1):uint() ~= 35 then return false end
  local t = transport_of(pinfo)
  local b = tvb:raw(0, math.min(len, 80))
  local st, _, f = parse_frame(b, 0, len <= 80 and t ~= "tcp")
  -- a TCP segment may hold the start of a frame only: a whole header will do
  local ok = (st == "frame" and f.checksum_ok) or (st == "need_more" and t == "tcp" and len >= 10)
  if not ok then return false end
  dissect(tvb, pinfo, tree, t, t ~= "tcp")
  return true
end

local udp_port = DissectorTable.get("udp.port")
for _, p in ipairs(PORTS.udp) do udp_port:add(p, top) end
local tcp_port = DissectorTable.get("tcp.port")
for _, p in ipairs(PORTS.tcp) do tcp_port:add(p, top) end
DissectorTable.get("wtap_encap"):add(wtap_encaps.USER0, top)
top:register_heuristic("udp", heuristic)
top:register_heuristic("tcp", heuristic)
