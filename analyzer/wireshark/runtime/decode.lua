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

-- The role the frame's layout alone gives (top::role_from_layout): a
-- response when only responses of its identifier, control and length exist
-- (or it is a read laid out as a device stream's push: the SkyDroid GAC,
-- which the document writes #TPUGCrGAC, client first), a request when only
-- requests do.
local function role_from_layout(dialect, f)
  local n, ctl = f.data_length, f.control and schar(f.control) or nil
  local request, response = false, false
  for _, d in ipairs({ "skydroid", "topotek" }) do
    local cmd = (dialect == "unknown" or d == dialect) and CATALOG[d][f.ident] or nil
    if cmd then
      for _, fm in ipairs(cmd.forms) do
        if fm.control == ctl and n >= fm.min_length and n <= fm.max_length then
          request = request or fm.role ~= "response"
          response = response or fm.role ~= "request"
        end
      end
    end
  end
  if response and not request then return "response" end
  if request and not response then return "request" end
  if response and ctl == "r" then
    for _, d in ipairs({ "skydroid", "topotek" }) do
      if (dialect == "unknown" or d == dialect) and STREAMS[d].push[f.ident] == "device" then
        return "response"
      end
    end
  end
  return "any"
end

local function fmt_number(v, d) return sfmt("%." .. d .. "f", v) end

local function all_printable(s)
  return not string.find(s, "[^\32-\126]")
end

-- Bytes as topdump's JSON carries them (top::escape): printable ASCII as it
-- is, \\ \r \n, and \xNN for the rest.
local function escape_bytes(s)
  if all_printable(s) and not string.find(s, "\\", 1, true) then return s end
  local out = {}
  for i = 1, #s do
    local c = sbyte(s, i)
    if c == 92 then out[i] = "\\\\"
    elseif c == 13 then out[i] = "\\r"
    elseif c == 10 then out[i] = "\\n"
    elseif c >= 32 and c < 127 then out[i] = schar(c)
    else out[i] = sfmt("\\x%02X", c) end
  end
  return table.concat(out)
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
  elseif k == "u8" then
    if #bytes ~= 1 then return bad("needs 1 bytes") end
    fv.integer = sbyte(bytes, 1)
    fv.value = scaled(fv.integer, spec)
    fv.valid = true
  elseif k == "be_i16" or k == "be_u16" then
    if #bytes ~= 2 then return bad("needs 2 bytes") end
    local u = sbyte(bytes, 1) * 256 + sbyte(bytes, 2)
    if k == "be_i16" and u >= 32768 then u = u - 65536 end
    fv.integer = u
    fv.value = scaled(u, spec)
    fv.valid = true
  elseif k == "nmea" then
    if #bytes < 2 then return bad("too short for a hemisphere and a coordinate") end
    local hemi = ssub(bytes, 1, 1)
    if hemi ~= "E" and hemi ~= "W" and hemi ~= "N" and hemi ~= "S" then
      return bad("hemisphere '" .. hemi .. "' is not N S E W")
    end
    -- Degrees in 3 digits east or west, 2 north or south, then mm.mmmm
    -- (decode.cpp: the 5.8.7 output is no such coordinate).
    local dd = (hemi == "E" or hemi == "W") and 3 or 2
    local coord = ssub(bytes, 2)
    local pattern = "^" .. string.rep("%d", dd + 2) .. "%.%d%d%d%d$"
    local raw = coord:match(pattern) and parse_number(coord) or nil
    if raw == nil or raw - math.floor(raw / 100.0) * 100.0 >= 60.0 then
      return bad("'" .. coord .. "' is not " .. (dd == 3 and "dddmm.mmmm" or "ddmm.mmmm"))
    end
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
  elseif k == "text" then
    return fv.text
  elseif k == "raw" then
    -- printable bytes as they are, binary ones (the Topotek ODZ) as hex pairs
    if all_printable(fv.text) then return fv.text end
    local hex = {}
    for i = 1, #fv.text do hex[i] = sfmt("%02X", sbyte(fv.text, i)) end
    return table.concat(hex, " ")
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

-- The field's key (top::field_key): its name, "x[1]" for a field of record 1.
local function field_key(fv)
  if fv.record then return fv.spec.name .. "[" .. fv.record .. "]" end
  return fv.spec.name
end

-- The records after a form's fields (decode.cpp check_records): as many as
-- the count field (the form's last, at data offset count_at) says and the
-- data holds; a count the data does not match is a data-length at the count.
local function decode_records(ctx, out, f, form, data, count_at, pos)
  local cf = form.fields[#form.fields]
  local quiet = { lowercase_reported = false, add = function() end }
  local count = decode_field(quiet, cf, ssub(data, count_at + 1, pos), 0)
  if not count.valid or count.none or count.integer < 0 then return end
  local width = 0
  for _, r in ipairs(form.record) do width = width + r.width end
  if width == 0 then return end
  local left = #data - pos
  local whole = math.floor(left / width)
  local n = count.integer
  if n * width ~= left then
    ctx.add("data-length", f.data_offset + count_at, cf.name .. " " .. n .. ": " .. n ..
            " record(s) of " .. width .. " byte(s) need " .. (n * width) .. ", " .. left .. " follow")
  end
  local records = n < whole and n or whole
  for i = 1, records do
    for _, r in ipairs(form.record) do
      local fv = decode_field(ctx, r, ssub(data, pos + 1, pos + r.width), f.data_offset + pos)
      fv.record = i
      out.fields[#out.fields + 1] = fv
      pos = pos + r.width
    end
  end
end

-- A client's frame in a length its document does not give that a form of
-- the field takes (decode.cpp note_field_length: ArduPilot's 14-char FAI):
-- a data-length of information naming the form's source.
local function note_field_length(ctx, out, f, cmd, form)
  if not form.evidence or cmd.field or form.role == "response" or out.role == "response" then
    return
  end
  local len = f.data_length
  local documented, allowed = false, {}
  for _, fm in ipairs(cmd.forms) do
    if not fm.evidence and fm.control == form.control then
      if len >= fm.min_length and len <= fm.max_length then return end
      documented = true
      allowed[#allowed + 1] = fm.min_length == fm.max_length and tostring(fm.min_length) or
                              (fm.min_length .. "-" .. fm.max_length)
    end
  end
  if not documented then return end
  out.findings[#out.findings + 1] = finding("data-length", f.data_offset, len .. " data byte(s); " ..
                                            f.ident .. " '" .. form.control .. "' takes " ..
                                            table.concat(allowed, ", ") .. " in " .. cmd.section ..
                                            "; field: " .. form.evidence, form.evidence, "info")
end

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
  note_field_length(ctx, out, f, cmd, form)
  local data = ssub(f.raw, f.data_offset + 1, f.data_offset + f.data_length)
  -- Among the forms of this shape from `form` on, the first whose fields
  -- validate (decode.cpp by_content: LAT/LON's field echo and 5.8.7 output).
  local same, first = {}, nil
  for i, fm in ipairs(cmd.forms) do
    if fm == form then first = i end
    if first and fm.control == form.control and role_fits(fm.role, out.role) and
       len >= fm.min_length and len <= fm.max_length then
      same[#same + 1] = fm
    end
  end
  if #same >= 2 then
    for _, fm in ipairs(same) do
      local trial = { findings = {}, fields = {} }
      local tctx = { lowercase_reported = false }
      function tctx.add(code, offset, message) trial.findings[#trial.findings + 1] = code end
      local p = 0
      for _, fs in ipairs(fm.fields) do
        if p >= #data and fs.width ~= 0 then break end
        local w = fs.width == 0 and (#data - p) or fs.width
        if p + w > #data then tctx.add("data-length", 0, "") break end
        decode_field(tctx, fs, ssub(data, p + 1, p + w), f.data_offset + p)
        p = p + w
      end
      if #trial.findings == 0 then
        form = fm
        break
      end
    end
  end
  out.form = form
  if form.role ~= "any" and out.role == "any" then out.role = form.role end

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
  local done, last = 0, 0
  for _, fs in ipairs(form.fields) do
    if pos >= #data and fs.width ~= 0 then break end
    local w = fs.width == 0 and (#data - pos) or fs.width
    if pos + w > #data then
      ctx.add("data-length", f.data_offset + pos, fs.name .. " needs " .. w .. " byte(s), " ..
              (#data - pos) .. " left")
      break
    end
    out.fields[#out.fields + 1] = decode_field(ctx, fs, ssub(data, pos + 1, pos + w), f.data_offset + pos)
    last = pos
    pos = pos + w
    done = done + 1
  end
  if form.record and done == #form.fields and done > 0 then
    decode_records(ctx, out, f, form, data, last, pos)
  end
  return out
end

-- The recorded form a device frame matches (top::recorded_form): its header
-- and address order; field evidence first. model "auto" matches every model.
local function recorded_form(dialect, model, f, sent)
  local order = (f.src == 85 or f.src == 80) and "request order" or "swapped"
  local ctl = f.control and schar(f.control) or nil
  local best = nil
  for _, x in ipairs(RECORDED) do
    if x.dialect == dialect and (model == "auto" or x.models[model]) and x.ident == f.ident and
       x.control == ctl and x.sent == sent and x.header == f.header and x.order == order then
      if not best or x.source == "field" then best = x end
    end
  end
  return best
end

-- A frame the device sent (the conversation says so): a recorded form of
-- real firmware completes its findings (top::note_device_form). A push in
-- the order its recorded form has (the C12's #tpUGCrGAC) is that device's
-- own form, not a reply that failed to swap: no note; other unswapped
-- device frames are noted; a recorded form names its evidence and makes a
-- tp-length info.
local function note_device_form(f, model, dec)
  local unswapped = role_from_addresses(f) == "request"
  local tp, un = nil, nil
  local function find_tp()
    tp = nil
    for _, x in ipairs(dec.findings) do
      if x.code == "tp-length" and x.severity ~= "info" then tp = x end
    end
  end
  for i, x in ipairs(dec.findings) do
    if x.code == "tp-length" and x.severity ~= "info" then tp = x end
    if x.code == "unswapped-addresses" then un = i end
  end
  if not unswapped and not tp then return end
  local streams = STREAMS[dec.dialect]
  local push = streams ~= nil and streams.push[f.ident] == "device"
  local rf = recorded_form(dec.dialect, model, f, push and "push" or "reply")
  local function source() return "; as recorded (" .. rf.source .. ")" end
  if unswapped and push and rf then
    if un then table.remove(dec.findings, un) end
    un = nil
    find_tp()
  elseif unswapped and not un then
    local msg
    if rf then
      msg = f.ident .. (push and " push" or " reply") .. " addressed " .. schar(f.src) .. " to " ..
            schar(f.dst) .. " (the request's order)" .. source()
    else
      msg = "a response addressed " .. schar(f.src) .. " to " .. schar(f.dst) ..
            " (the request's order; some simulators)"
    end
    dec.findings[#dec.findings + 1] = finding("unswapped-addresses", 3, msg)
    un = #dec.findings
    find_tp()
  elseif un and rf then
    dec.findings[un].message = dec.findings[un].message .. source()
  end
  if not rf then return end
  if un then dec.findings[un].quirk = rf.evidence end
  if tp then
    tp.severity = "info"
    tp.quirk = rf.evidence
    tp.message = tp.message .. source()
  end
end

local function summary(dec)
  local form = dec.form
  if form and form.none and #dec.fields > 0 and dec.fields[1].none and form.note ~= "" then
    return "none (" .. form.note .. ")"
  end
  local parts = {}
  for _, fv in ipairs(dec.fields) do parts[#parts + 1] = field_key(fv) .. " " .. format_value(fv) end
  return table.concat(parts, ", ")
end

