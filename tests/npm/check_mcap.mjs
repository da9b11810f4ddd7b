// The npm oracle of bimloc's MCAP (issue 29 §1, §2): Foxglove's own MCAP library (@mcap/core,
// with @mcap/support's zstd / lz4 decompression) and ROS 2 CDR decoder
// (@foxglove/rosmsg2-serialization, by the ros2msg schemas in the file), installed by
// run_oracle.sh into ORACLE_DIR. Modes:
//   read FILE.mcap OURS.json      every record of OUR file valid (CRCs checked), its summary and
//                                 chunk indexes present, every message decoded by Foxglove equal
//                                 to what our reader decoded (OURS.json: tests/npm/ros2_dump.cpp)
//   write PREFIX                  THEIR files, written by @mcap/core's writer: PREFIX_{zstd,lz4}_
//                                 {summary,nosummary}.mcap and PREFIX_expected.json (the messages)
//   compare EXPECTED.json OURS.json  what our reader decoded of their file equals what they wrote
import fs from "node:fs";
import { createRequire } from "node:module";

const require = createRequire((process.env.ORACLE_DIR ?? ".") + "/");
const { McapIndexedReader, McapStreamReader, McapWriter } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader, MessageWriter } = require("@foxglove/rosmsg2-serialization");

function fail(what) {
  console.error("check_mcap: " + what);
  process.exit(1);
}

const CRC_TABLE = (() => {
  const t = new Uint32Array(256);
  for (let n = 0; n < 256; n++) {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    t[n] = c >>> 0;
  }
  return t;
})();
function crc32(bytes) {
  let c = 0xffffffff;
  for (let i = 0; i < bytes.length; i++) c = CRC_TABLE[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

// `expected` (JSON) against `actual` (a decoded message or JSON): every key of expected.
function compare(expected, actual, path) {
  if (expected === null) return;
  if (typeof expected === "object" && !Array.isArray(expected) && "$bytes_crc32" in expected) {
    if (actual instanceof Uint8Array || Array.isArray(actual)) {
      const bytes = Uint8Array.from(actual);
      if (bytes.length !== expected.$bytes_length) fail(`${path}: ${bytes.length} bytes, expected ${expected.$bytes_length}`);
      if (crc32(bytes) !== expected.$bytes_crc32) fail(`${path}: the bytes differ (CRC-32)`);
      return;
    }
    if (actual?.$bytes_crc32 !== expected.$bytes_crc32 || actual?.$bytes_length !== expected.$bytes_length)
      fail(`${path}: the bytes differ: ${JSON.stringify(actual)} vs ${JSON.stringify(expected)}`);
    return;
  }
  if (Array.isArray(expected)) {
    if (actual == null || actual.length !== expected.length) fail(`${path}: length ${actual?.length}, expected ${expected.length}`);
    expected.forEach((e, i) => compare(e, actual[i], `${path}[${i}]`));
    return;
  }
  if (typeof expected === "object") {
    if (actual == null || typeof actual !== "object") fail(`${path}: missing`);
    for (const key of Object.keys(expected)) compare(expected[key], actual[key], `${path}.${key}`);
    return;
  }
  const a = typeof actual === "bigint" ? Number(actual) : actual;
  if (a !== expected) fail(`${path}: ${a} (${typeof actual}), expected ${expected}`);
}

// The messages of a dump keyed by "topic log_time #n" (n: among equal keys, in order).
function keyed(messages) {
  const seen = new Map();
  const out = new Map();
  for (const m of messages) {
    const base = `${m.topic} ${m.log_time}`;
    const n = seen.get(base) ?? 0;
    seen.set(base, n + 1);
    out.set(`${base} #${n}`, m);
  }
  return out;
}

function readable(file) {
  const fd = fs.openSync(file, "r");
  const size = fs.fstatSync(fd).size;
  return {
    size: async () => BigInt(size),
    read: async (offset, length) => {
      const buf = new Uint8Array(Number(length));
      fs.readSync(fd, buf, 0, Number(length), Number(offset));
      return buf;
    },
  };
}

async function read(file, oursFile) {
  const decompressHandlers = await loadDecompressHandlers();
  const ours = JSON.parse(fs.readFileSync(oursFile, "utf8"));
  // 1. Record by record, CRCs checked: the whole file is valid MCAP.
  const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  stream.append(fs.readFileSync(file));
  const records = {};
  let rec;
  while ((rec = stream.nextRecord())) records[rec.type] = (records[rec.type] ?? 0) + 1;
  if (!stream.done()) fail(`${file}: the stream reader did not reach the end`);
  for (const type of ["Header", "Schema", "Channel", "Message", "MessageIndex", "ChunkIndex", "Statistics", "SummaryOffset", "DataEnd", "Footer"])
    if (!records[type]) fail(`${file}: no ${type} record (${JSON.stringify(records)})`);
  // 2. Through the summary: every message decoded by the schema it names.
  const reader = await McapIndexedReader.Initialize({ readable: readable(file), decompressHandlers });
  if (reader.chunkIndexes.length === 0) fail(`${file}: no chunk index`);
  for (const ci of reader.chunkIndexes) if (ci.compression !== "zstd") fail(`${file}: a chunk compressed with '${ci.compression}', not zstd`);
  if (reader.header.profile !== "ros2") fail(`${file}: profile '${reader.header.profile}'`);
  const decoders = new Map();
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    if (!schema) fail(`${file}: channel ${channel.topic} has no schema`);
    if (schema.encoding !== "ros2msg" || channel.messageEncoding !== "cdr")
      fail(`${file}: ${channel.topic}: schema encoding ${schema.encoding}, message encoding ${channel.messageEncoding}`);
    if (!channel.metadata.get("offered_qos_profiles")) fail(`${file}: ${channel.topic} has no offered_qos_profiles`);
    decoders.set(id, new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true })));
  }
  const expected = keyed(ours.messages);
  const counts = new Map();
  const seen = new Map();
  let n = 0;
  for await (const m of reader.readMessages({ validateCrcs: true })) {
    const channel = reader.channelsById.get(m.channelId);
    const base = `${channel.topic} ${m.logTime}`;
    const k = seen.get(base) ?? 0;
    seen.set(base, k + 1);
    const mine = expected.get(`${base} #${k}`);
    if (!mine) fail(`${file}: ${base}: a message our reader did not give`);
    const decoded = decoders.get(m.channelId).readMessage(m.data);
    compare(mine.message, decoded, `${channel.topic}@${m.logTime}`);
    counts.set(channel.topic, (counts.get(channel.topic) ?? 0) + 1);
    n++;
  }
  if (n !== ours.messages.length) fail(`${file}: ${n} messages through @mcap/core, ${ours.messages.length} through ours`);
  for (const [id, count] of reader.statistics.channelMessageCounts) {
    const topic = reader.channelsById.get(id).topic;
    if (Number(count) !== (counts.get(topic) ?? 0)) fail(`${file}: statistics say ${count} on ${topic}, read ${counts.get(topic)}`);
  }
  console.log(`${file}: ${n} messages on ${reader.channelsById.size} channels decoded by Foxglove, equal to ours; records ${JSON.stringify(records)}`);
}

// Their definitions, written here from the ROS 2 .msg files (not taken from ours).
const ODOMETRY = `std_msgs/Header header
string child_frame_id
geometry_msgs/PoseWithCovariance pose
geometry_msgs/TwistWithCovariance twist
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: geometry_msgs/PoseWithCovariance
Pose pose
float64[36] covariance
================================================================================
MSG: geometry_msgs/Pose
Point position
Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
================================================================================
MSG: geometry_msgs/TwistWithCovariance
Twist twist
float64[36] covariance
================================================================================
MSG: geometry_msgs/Twist
Vector3 linear
Vector3 angular
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
`;
const POINTCLOUD2 = `std_msgs/Header header
uint32 height
uint32 width
PointField[] fields
bool is_bigendian
uint32 point_step
uint32 row_step
uint8[] data
bool is_dense
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: sensor_msgs/PointField
uint8 FLOAT32 = 7
string name
uint32 offset
uint8 datatype
uint32 count
`;
const TFMESSAGE = `geometry_msgs/TransformStamped[] transforms
================================================================================
MSG: geometry_msgs/TransformStamped
std_msgs/Header header
string child_frame_id
Transform transform
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: geometry_msgs/Transform
Vector3 translation
Quaternion rotation
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
`;

// A fixed pseudo-random stream (no Math.random: the files are the same on every run).
function lcg(seed) {
  let s = seed >>> 0;
  return () => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 4294967296);
}

function theirMessages() {
  const rand = lcg(29);
  const out = [];
  const t0 = 1700000000n * 1000000000n;
  for (let i = 0; i < 300; i++) {
    const ns = t0 + BigInt(i) * 20000000n;
    const stamp = { sec: Number(ns / 1000000000n), nanosec: Number(ns % 1000000000n) };
    const yaw = rand() * 6;
    out.push({ topic: "/odom", log_time: ns, message: {
      header: { stamp, frame_id: "odom" }, child_frame_id: "base_link",
      pose: { pose: { position: { x: rand() * 10, y: -rand(), z: 0 }, orientation: { x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) } },
              covariance: Array.from({ length: 36 }, (_, k) => (k % 7 === 0 ? 0.001 * (k + 1) : 0)) },
      twist: { twist: { linear: { x: rand(), y: 0, z: 0 }, angular: { x: 0, y: 0, z: rand() - 0.5 } }, covariance: new Array(36).fill(0) } } });
    out.push({ topic: "/tf", log_time: ns, message: { transforms: [
      { header: { stamp, frame_id: "odom" }, child_frame_id: "base_link",
        transform: { translation: { x: i * 0.01, y: 0.5, z: 0 }, rotation: { x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) } } },
      { header: { stamp, frame_id: "base_link" }, child_frame_id: "velodyne",
        transform: { translation: { x: 0.1, y: 0, z: 0.6 }, rotation: { x: 0, y: 0, z: 0, w: 1 } } }] } });
    if (i % 5 === 0) {
      const points = 200 + (i % 7);
      const data = new Uint8Array(points * 13);
      for (let k = 0; k < data.length; k++) data[k] = Math.floor(rand() * 256);
      out.push({ topic: "/velodyne_points", log_time: ns + 1000n, message: {
        header: { stamp, frame_id: "velodyne" }, height: 1, width: points,
        fields: [{ name: "x", offset: 0, datatype: 7, count: 1 }, { name: "y", offset: 4, datatype: 7, count: 1 },
                 { name: "z", offset: 8, datatype: 7, count: 1 }, { name: "ring", offset: 12, datatype: 2, count: 1 }],
        is_bigendian: false, point_step: 13, row_step: 13 * points, data, is_dense: true } });
    }
  }
  return out;
}

async function write(prefix) {
  const lz4js = require("lz4js");
  const { default: zstd } = { default: require("@foxglove/wasm-zstd") };
  await zstd.isLoaded;
  const types = { "/odom": ["nav_msgs/msg/Odometry", ODOMETRY], "/tf": ["tf2_msgs/msg/TFMessage", TFMESSAGE],
                  "/velodyne_points": ["sensor_msgs/msg/PointCloud2", POINTCLOUD2] };
  const messages = theirMessages();
  for (const compression of ["zstd", "lz4"]) {
    for (const summary of [true, false]) {
      const file = `${prefix}_${compression}_${summary ? "summary" : "nosummary"}.mcap`;
      const chunks = [];
      let position = 0n;
      const writable = { position: () => position, write: async (buf) => { chunks.push(Buffer.from(buf)); position += BigInt(buf.byteLength); } };
      const writer = new McapWriter({
        writable, chunkSize: 64 * 1024, useStatistics: summary, useSummaryOffsets: summary, useChunkIndex: summary,
        useMessageIndex: summary, repeatSchemas: summary, repeatChannels: summary,
        compressChunk: (data) => ({ compression,
          compressedData: compression === "zstd" ? new Uint8Array(zstd.compress(data, 3)) : Uint8Array.from(lz4js.compress(data)) }),
      });
      await writer.start({ profile: "ros2", library: "npm oracle" });
      const channels = {};
      const encoders = {};
      for (const [topic, [type, text]] of Object.entries(types)) {
        const schemaId = await writer.registerSchema({ name: type, encoding: "ros2msg", data: new TextEncoder().encode(text) });
        channels[topic] = await writer.registerChannel({ topic, schemaId, messageEncoding: "cdr", metadata: new Map([["offered_qos_profiles", ""]]) });
        encoders[topic] = new MessageWriter(parse(text, { ros2: true }));
      }
      const sequence = {};
      for (const m of messages)
        await writer.addMessage({ channelId: channels[m.topic], sequence: (sequence[m.topic] = (sequence[m.topic] ?? 0) + 1),
                                  logTime: m.log_time, publishTime: m.log_time, data: encoders[m.topic].writeMessage(m.message) });
      await writer.end();
      fs.writeFileSync(file, Buffer.concat(chunks));
    }
  }
  const json = messages.map((m) => ({ topic: m.topic, log_time: String(m.log_time), message: m.message }));
  fs.writeFileSync(`${prefix}_expected.json`, JSON.stringify({ messages: json }, (key, value) =>
    value instanceof Uint8Array ? { $bytes_crc32: crc32(value), $bytes_length: value.length } : value));
  console.log(`wrote ${prefix}_{zstd,lz4}_{summary,nosummary}.mcap: ${messages.length} messages each`);
}

function compareDumps(expectedFile, oursFile) {
  const expected = JSON.parse(fs.readFileSync(expectedFile, "utf8")).messages;
  const ours = JSON.parse(fs.readFileSync(oursFile, "utf8"));
  if (ours.messages.length !== expected.length) fail(`${oursFile}: ${ours.messages.length} messages, they wrote ${expected.length}`);
  const mine = keyed(ours.messages);
  for (const [key, m] of keyed(expected)) {
    const got = mine.get(key);
    if (!got) fail(`${oursFile}: ${key}: written by @mcap/core, not read by ours`);
    compare(m.message, got.message, key);
  }
  console.log(`${oursFile}: ${expected.length} messages read by ours, equal to what @mcap/core wrote`);
}

const [mode, a, b] = process.argv.slice(2);
if (mode === "read") await read(a, b);
else if (mode === "write") await write(a);
else if (mode === "compare") compareDumps(a, b);
else fail("usage: check_mcap.mjs read FILE OURS.json | write PREFIX | compare EXPECTED.json OURS.json");
