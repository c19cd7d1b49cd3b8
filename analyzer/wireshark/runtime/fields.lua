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

