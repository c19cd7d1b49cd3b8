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

