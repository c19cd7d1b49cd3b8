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

