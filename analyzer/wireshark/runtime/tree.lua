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
  local label = field_key(fv) .. ": " .. format_value(fv)
  local r = tvb(base_off + fv.offset, fv.length)
  local pf = CATALOG_FIELDS[s.abbrev]
  if fv.none or not fv.valid or not pf then
    sub:add(r, label)
    return
  end
  local k = s.kind
  local v = fv.value
  if CATALOG_VTYPE[s.abbrev] == "string" then
    if k == "text" then
      v = fv.text
    elseif k == "raw" then
      v = escape_bytes(fv.text)  -- binary bytes (the Topotek ODZ) as topdump's JSON has them
    else
      v = format_value(fv)
    end
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
  -- the conversation says the device sent it (top::decode with a response role)
  if role == "response" then note_device_form(f, pk.model, dec) end
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
    -- a record's fields (the Topotek ODR detections) under "record n"
    local record_width = 0
    for _, r in ipairs(dec.form and dec.form.record or {}) do record_width = record_width + r.width end
    local rec_tree, rec_n = nil, 0
    for _, fv in ipairs(dec.fields) do
      local parent = sub
      if fv.record then
        if fv.record ~= rec_n then
          rec_n = fv.record
          rec_tree = sub:add(tvb(off + fv.offset, record_width), "record " .. rec_n)
        end
        parent = rec_tree
      end
      add_field(parent, tvb, off, fv)
    end
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
