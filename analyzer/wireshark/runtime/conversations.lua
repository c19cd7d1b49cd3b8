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
    -- device_dir: the direction the device sends in (0: from `first`), nil
    -- until the ports or a frame say (conversations.cpp, learn_device)
    c = { first = a, same = a == b, votes = { skydroid = 0, topotek = 0 }, observed = 0,
          port = "unknown", pending = {} }
    if transport ~= "serial" then
      local d1 = PORT_DIALECT[pinfo.src_port]
      if d1 then c.port = d1 end
      local d2 = PORT_DIALECT[pinfo.dst_port]
      if d2 then c.port = d2 end
      local s_dev = PORT_ROLE[pinfo.src_port] == "device"
      local d_dev = PORT_ROLE[pinfo.dst_port] == "device"
      if s_dev ~= d_dev then c.device_dir = s_dev and 0 or 1 end
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

-- Learns which direction the device sends in from a frame of direction
-- dir, when the ports did not say (topdump's learn_device,
-- analyzer/session/src/requests.cpp): a frame addressed to a client, one whose
-- layout only a response has (a 12-char attitude push, even from a device
-- that keeps the request's address order, as a real C12 pushes
-- #tpUGCrGAC), or one that answers a pending request of the other
-- direction, comes from the device; a frame whose layout only a request
-- has, or a stream switch (GAA, GIA, FAE write), comes from a client.
local function learn_device(c, dir, f, dialect)
  -- Both ends the same (a recording without ports): the addresses decide.
  if c.same then return end
  if role_from_addresses(f) == "response" then
    c.device_dir = dir
    return
  end
  local layout = role_from_layout(dialect, f)
  if layout == "response" then
    c.device_dir = dir
    return
  elseif layout == "request" then
    c.device_dir = 1 - dir
    return
  end
  for _, p in ipairs(c.pending) do
    if p.dir ~= dir and p.ident == f.ident then
      c.device_dir = dir
      return
    end
  end
  if f.control == 119 and dialect ~= "unknown" and STREAMS[dialect].switch[f.ident] then
    c.device_dir = 1 - dir
  end
end

-- The dialect and role topdump gives this frame, updating the conversation:
-- the device's frames are responses and pushes whatever their address order
-- (real C12s push #tpUGCrGAC, client first), the client's are requests;
-- "any" while the conversation has not shown which end is the device.
local function judge_frame(c, dir, f, ts)
  if c.observed < 64 then
    local v = dialect_from_frame(f)
    if v ~= "unknown" then c.votes[v] = c.votes[v] + 1 end
    c.observed = c.observed + 1
  end
  local dialect = current_dialect(c)
  if dialect == "unknown" then dialect = dialect_from_frame(f) end
  if c.device_dir == nil then learn_device(c, dir, f, dialect) end
  local role = "any"
  if c.device_dir ~= nil then role = dir == c.device_dir and "response" or "request" end
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

