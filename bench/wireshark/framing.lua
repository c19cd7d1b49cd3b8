-- A hand-written, framing-only TOP dissector: what users wrote before
-- `topdump wireshark`, kept as the baseline of bench/wireshark/run.sh. It
-- splits a datagram into #TP/#tp frames and shows header, addresses,
-- length, control, identifier, data and checksum; no catalog, no fields, no
-- extended headers, no lying lengths, no expert info.
local p = Proto("topraw", "TOP framing")
local f_hdr = ProtoField.string("topraw.header", "Header")
local f_src = ProtoField.string("topraw.src", "Source")
local f_dst = ProtoField.string("topraw.dst", "Destination")
local f_len = ProtoField.uint8("topraw.length", "Length")
local f_ctl = ProtoField.string("topraw.control", "Control")
local f_id = ProtoField.string("topraw.ident", "Identifier")
local f_data = ProtoField.string("topraw.data", "Data")
local f_cs = ProtoField.string("topraw.checksum", "Checksum")
p.fields = { f_hdr, f_src, f_dst, f_len, f_ctl, f_id, f_data, f_cs }

function p.dissector(tvb, pinfo, tree)
  local n, off, idents = tvb:len(), 0, {}
  while off + 12 <= n do
    local c = tvb(off, 1):uint()
    if c == 13 or c == 10 then
      off = off + 1
    else
      local len = tonumber(tvb(off + 5, 1):string(), 16)
      if c ~= 35 or not len or off + 12 + len > n then break end
      local t = tree:add(p, tvb(off, 12 + len))
      t:add(f_hdr, tvb(off, 3))
      t:add(f_src, tvb(off + 3, 1))
      t:add(f_dst, tvb(off + 4, 1))
      t:add(f_len, tvb(off + 5, 1), len)
      t:add(f_ctl, tvb(off + 6, 1))
      t:add(f_id, tvb(off + 7, 3))
      if len > 0 then t:add(f_data, tvb(off + 10, len)) end
      t:add(f_cs, tvb(off + 10 + len, 2))
      idents[#idents + 1] = tvb(off + 7, 3):string()
      off = off + 12 + len
    end
  end
  pinfo.cols.protocol = "TOP"
  pinfo.cols.info:set(table.concat(idents, " "))
  return n
end

local udp = DissectorTable.get("udp.port")
for _, port in ipairs({ 5000, 9002, 9003, 9004, 12580 }) do udp:add(port, p) end
