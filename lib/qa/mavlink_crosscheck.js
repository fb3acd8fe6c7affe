// Copyright 2026 gr-rfseek authors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Cross-check of the module's MAVLink codec (lib/mavlink.cc) against node-mavlink, an
// independent implementation (ArduPilot's JavaScript one), both ways, on seeded random
// messages of every type the codec decodes:
//   A. frames we encode (rfseek_mavlink_tool encode) pass node-mavlink's CRC check,
//      decode there to the same header and fields, re-encode there to the same bytes
//      (MAVLink 2; MAVLink 1 where node-mavlink writes the same length), and their
//      signatures verify there with the key (and fail with a tampered byte);
//   B. frames node-mavlink encodes (signed or not, v2 and v1) decode here to the fields
//      node-mavlink reads back from them;
//   C. a wrong key, a replayed timestamp, a stale new stream and a corrupted byte are
//      refused here and counted;
//   D. CRC_EXTRA of every message in both dialect tables agree.
//
// Usage: node mavlink_crosscheck.js TOOL [COUNT per direction] [SEED]
// (NODE_PATH must reach node-mavlink: scripts/setup.sh installs it into <build>/node.)
'use strict';

const { spawnSync } = require('child_process');

let mav;
try {
    mav = require('node-mavlink');
} catch (e) {
    console.error('node-mavlink is not installed where NODE_PATH points (' +
        (process.env.NODE_PATH || 'unset') + '). `bash scripts/setup.sh test` installs ' +
        'it into <build>/node; or run `npm ci` in <build>/node with lib/qa/node/package*.json.');
    process.exit(1);
}

const tool = process.argv[2];
const count = Number(process.argv[3] || 12000);
const seed = Number(process.argv[4] || 20261125);
const keyHex = '4d2a'.repeat(16);
const key = Buffer.from(keyHex, 'hex');
const REGISTRY = Object.assign({}, mav.minimal.REGISTRY, mav.common.REGISTRY,
    mav.ardupilotmega.REGISTRY);

let failures = 0;
function fail(msg) {
    if (failures < 20)
        console.error('FAIL: ' + msg);
    failures++;
}

function run(args, input) {
    const r = spawnSync(tool, args, { input, encoding: 'utf8', maxBuffer: 1 << 30 });
    if (r.status !== 0)
        throw new Error(tool + ' ' + args.join(' ') + ' failed: ' + r.stderr);
    return r.stdout.trim().split('\n').filter(l => l.length).map(l => JSON.parse(l));
}

// A value as both sides print it: BigInt as a decimal string, arrays element-wise.
function norm(v) {
    if (typeof v === 'bigint')
        return v.toString();
    if (Array.isArray(v))
        return v.map(norm);
    return v;
}

function same(a, b) {
    return JSON.stringify(norm(a)) === JSON.stringify(norm(b));
}

function protocolOf(buffer, sysid, compid) {
    return buffer[0] === 0xFD ? new mav.MavLinkProtocolV2(sysid, compid, buffer[2])
        : new mav.MavLinkProtocolV1(sysid, compid);
}

// Decode one whole frame with node-mavlink: header, data, signature.
function nodeDecode(buffer) {
    const protocol = protocolOf(buffer);
    const header = protocol.header(buffer);
    const clazz = REGISTRY[header.msgid];
    const data = protocol.data(protocol.payload(buffer), clazz);
    return { header, clazz, data, signature: protocol.signature ? protocol.signature(buffer, header) : null };
}

function fieldsOf(clazz, data, v1) {
    const out = {};
    for (const f of clazz.FIELDS)
        out[f.source] = (v1 && f.extension) ? undefined : norm(data[f.name]);
    return out;
}

// node-mavlink's own splitter over a byte stream: the frames it finds valid.
function split(bytes) {
    return new Promise((resolve, reject) => {
        const splitter = new mav.MavLinkPacketSplitter();
        const found = [];
        splitter.on('data', p => found.push(p.buffer));
        splitter.on('error', reject);
        splitter.on('end', () => resolve({ found, invalid: splitter.invalidPackages, unknown: splitter.unknownPackagesCount }));
        splitter.end(bytes);
        splitter.resume();
    });
}

async function ourFramesThere() {
    const lines = run(['encode', String(seed), String(count), keyHex]);
    const frames = lines.map(l => Buffer.from(l.frame, 'hex'));
    const { found, invalid, unknown } = await split(Buffer.concat(frames));
    if (found.length !== lines.length || invalid || unknown)
        fail(`node-mavlink's splitter found ${found.length} valid frames of ${lines.length} ` +
            `(${invalid} invalid, ${unknown} unknown)`);
    let reencoded = 0, signedChecked = 0, zeroFirstByte = 0;
    const types = new Set();
    lines.forEach((l, i) => {
        const buffer = frames[i];
        if (found[i] && !found[i].equals(buffer))
            fail(`frame ${i}: the splitter cut different bytes`);
        const { header, clazz, data, signature } = nodeDecode(buffer);
        types.add(clazz.MSG_NAME);
        if (clazz.MSG_NAME !== l.name || header.seq !== l.seq || header.sysid !== l.sysid ||
            header.compid !== l.compid)
            fail(`frame ${i} (${l.name}): header differs: ${JSON.stringify(header)}`);
        const theirs = fieldsOf(clazz, data, l.version === 1);
        for (const f of clazz.FIELDS) {
            if (l.version === 1 && f.extension)
                continue;
            if (!same(theirs[f.source], l.fields[f.source]))
                fail(`frame ${i} (${l.name}.${f.source}): ours ${JSON.stringify(l.fields[f.source])}, ` +
                    `node-mavlink ${JSON.stringify(theirs[f.source])}`);
        }
        if (l.signed) {
            signedChecked++;
            if (!signature || !signature.matches(key) || signature.linkId !== l.link_id ||
                signature.timestamp !== l.timestamp)
                fail(`frame ${i} (${l.name}): signature not verified by node-mavlink`);
            const tampered = Buffer.from(buffer);
            tampered[tampered.length - 1] ^= 0x01;
            if (new mav.MavLinkPacketSignature(tampered).matches(key))
                fail(`frame ${i}: a tampered signature verified`);
        }
        // Re-encode there with the same header: the same bytes (v1 frames of messages
        // with extensions excepted: node-mavlink puts the extensions in them).
        const hasExt = clazz.FIELDS.some(f => f.extension);
        if (l.version === 2 || !hasExt) {
            const protocol = protocolOf(buffer, l.sysid, l.compid);
            let again = protocol.serialize(data, l.seq);
            if (l.signed) {
                again = Buffer.concat([again, Buffer.alloc(13)]);
                const s = new mav.MavLinkPacketSignature(again);
                s.linkId = l.link_id;
                s.timestamp = l.timestamp;
                s.signature = s.calculate(key);
            }
            // The protocol keeps the first payload byte of an all-zero payload;
            // node-mavlink 2.3 sends none. Both decode the same: compared as such.
            const zeroPayload = l.version === 2 && buffer[1] === 1 && buffer[10] === 0 && again[1] === 0;
            if (zeroPayload)
                zeroFirstByte++;
            else if (!again.equals(buffer))
                fail(`frame ${i} (${l.name} v${l.version}): node-mavlink re-encodes ` +
                    `${again.toString('hex')}, we wrote ${l.frame}`);
            reencoded++;
        }
    });
    console.log(`A. ${lines.length} frames encoded here, ${types.size} types: decoded by ` +
        `node-mavlink; ${reencoded - zeroFirstByte} re-encoded there byte for byte, ` +
        `${zeroFirstByte} all-zero payloads there with the first byte cut (the protocol ` +
        `keeps it, as we do); ${signedChecked} signatures verified there`);
}

// A small seeded generator (mulberry32), so that runs repeat.
function rng32(s) {
    let a = s >>> 0;
    return () => {
        a = (a + 0x6D2B79F5) >>> 0;
        let t = a;
        t = Math.imul(t ^ (t >>> 15), t | 1);
        t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
        return ((t ^ (t >>> 14)) >>> 0);
    };
}

function randomValue(next, type) {
    const zero = next() % 3 === 0;
    const f32 = new Float32Array(1);
    switch (type) {
    case 'char': return String.fromCharCode(32 + next() % 95);
    case 'float':
        if (zero) return 0;
        f32[0] = (next() % 2 ? -1 : 1) * (next() / 4294967296 + 0.5) * Math.pow(2, (next() % 60) - 30);
        return f32[0];
    case 'double': return zero ? 0 : (next() / 4294967296 - 0.5) * 1e6;
    case 'uint64_t': return zero ? 0n : (BigInt(next()) << 32n) | BigInt(next());
    case 'int64_t': return zero ? 0n : BigInt.asIntN(64, (BigInt(next()) << 32n) | BigInt(next()));
    }
    const bits = { uint8_t: 8, int8_t: 8, uint16_t: 16, int16_t: 16, uint32_t: 32, int32_t: 32,
        uint8_t_mavlink_version: 8 }[type];
    if (zero) return 0;
    const u = bits === 32 ? next() : next() % (1 << bits);
    return type.startsWith('int') && u >= Math.pow(2, bits - 1) ? u - Math.pow(2, bits) : u;
}

function randomMessage(next, clazz) {
    const m = new clazz();
    for (const f of clazz.FIELDS) {
        if (f.type === 'char[]') {
            let text = '';
            const n = next() % (f.length + 1);
            for (let i = 0; i < n; i++) text += randomValue(next, 'char');
            m[f.name] = text;
        } else if (f.type.endsWith('[]')) {
            const base = f.type.slice(0, -2);
            m[f.name] = Array.from({ length: f.length }, () => randomValue(next, base));
        } else {
            m[f.name] = randomValue(next, f.type);
        }
    }
    return m;
}

function theirFramesHere(ids) {
    const next = rng32(seed ^ 0x5eed);
    const expected = [];
    const hex = [];
    let timestamp = 1e9;
    for (let n = 0; n < count; n++) {
        const clazz = REGISTRY[ids[n % ids.length]];
        const m = randomMessage(next, clazz);
        const sysid = 1 + next() % 255, compid = 1 + next() % 255, seq = n % 256;
        const v1 = clazz.MSG_ID < 256 && next() % 10 === 0;
        const protocol = v1 ? new mav.MavLinkProtocolV1(sysid, compid)
            : new mav.MavLinkProtocolV2(sysid, compid, next() % 3 === 0 ? 1 : 0);
        let buffer = protocol.serialize(m, seq);
        const signed = !v1 && (buffer[2] & 1) === 1;
        const linkId = next() % 256;
        timestamp += 1 + next() % 1000;
        if (signed) {
            buffer = Buffer.concat([buffer, Buffer.alloc(13)]);
            const s = new mav.MavLinkPacketSignature(buffer);
            s.linkId = linkId;
            s.timestamp = timestamp;
            s.signature = s.calculate(key);
        }
        const back = nodeDecode(buffer);
        expected.push({ name: clazz.MSG_NAME, sysid, compid, seq, signed, linkId, timestamp,
            version: v1 ? 1 : 2, fields: fieldsOf(clazz, back.data, false) });
        hex.push(buffer.toString('hex'));
    }
    // C. refusals, after the stream (the parser keeps its replay state).
    const wrongKey = Buffer.from('11'.repeat(32), 'hex');
    const clazz = REGISTRY[ids[0]];
    const mk = (ts, k, sysid) => {
        let b = new mav.MavLinkProtocolV2(sysid, 1, 1).serialize(randomMessage(next, clazz), 0);
        b = Buffer.concat([b, Buffer.alloc(13)]);
        const s = new mav.MavLinkPacketSignature(b);
        s.linkId = 0; s.timestamp = ts; s.signature = s.calculate(k);
        return b;
    };
    const good = mk(timestamp + 10, key, 7);
    const corrupted = Buffer.from(good); corrupted[11] ^= 0x40;
    const refusals = [
        ['a frame signed with another key', mk(timestamp + 5, wrongKey, 7), 'bad_signature'],
        ['a good signed frame', good, null],
        ['the same frame again (replay)', good, 'replayed'],
        ['a new stream more than a minute older than the newest', mk(timestamp - 7000000, key, 9), 'replayed'],
        ['a corrupted byte', corrupted, 'bad_crc'],
    ];
    for (const r of refusals) hex.push(r[1].toString('hex'));

    const lines = run(['decode', keyHex], hex.join('\n') + '\n');
    if (lines.length !== hex.length) fail(`decode printed ${lines.length} lines for ${hex.length}`);
    let decoded = 0, signedHere = 0;
    expected.forEach((e, i) => {
        const l = lines[i];
        if (!l || l.frames.length !== 1) {
            fail(`node frame ${i} (${e.name} v${e.version}${e.signed ? ', signed' : ''}) ` +
                `refused here: ${JSON.stringify(l)} ${hex[i]}`);
            return;
        }
        const f = l.frames[0];
        if (f.name !== e.name || f.sysid !== e.sysid || f.compid !== e.compid || f.seq !== e.seq ||
            f.version !== e.version || f.signed !== e.signed ||
            (e.signed && (f.link_id !== e.linkId || f.timestamp !== e.timestamp)))
            fail(`node frame ${i} (${e.name}): header differs here: ${JSON.stringify(f)}`);
        for (const k of Object.keys(e.fields))
            if (!same(f.fields[k], e.fields[k]))
                fail(`node frame ${i} (${e.name}.${k}): node-mavlink ${JSON.stringify(e.fields[k])}, ` +
                    `here ${JSON.stringify(f.fields[k])}`);
        decoded++;
        if (e.signed) signedHere++;
    });
    refusals.forEach((r, j) => {
        const l = lines[expected.length + j];
        const ok = r[2] === null ? l.frames.length === 1 : (l.frames.length === 0 && l[r[2]] >= 1);
        if (!ok) fail(`${r[0]}: expected ${r[2] || 'accepted'}, got ${JSON.stringify(l)}`);
    });
    console.log(`B. ${count} frames encoded by node-mavlink: ${decoded} decoded here to the ` +
        `same fields (${signedHere} signed, verified here)`);
    console.log(`C. ${refusals.length - 1} bad frames refused here (wrong key, replay, stale ` +
        `stream, corrupted byte), the good signed one accepted`);
}

function crcExtras(types) {
    const magic = mav.MSG_ID_MAGIC_NUMBER;
    let compared = 0;
    for (const t of types.messages) {
        if (magic[t.id] !== t.crc_extra)
            fail(`${t.name}: CRC_EXTRA ${t.crc_extra} here, ${magic[t.id]} in node-mavlink`);
        if (!REGISTRY[t.id] || REGISTRY[t.id].MSG_NAME !== t.name)
            fail(`${t.name}: id ${t.id} is not that message in node-mavlink`);
    }
    // Our dialect table (ardupilotmega.xml and its includes) against node-mavlink's
    // classes of the same dialect (its magic-number table merges every dialect, where
    // some ids mean other messages).
    const onlyHere = [], differ = [];
    const ours = new Set();
    for (const [id, crc] of types.frames) {
        ours.add(id);
        if (!REGISTRY[id]) { onlyHere.push(id); continue; }
        compared++;
        if (REGISTRY[id].MAGIC_NUMBER !== crc) differ.push(id + ' ' + REGISTRY[id].MSG_NAME);
    }
    const onlyThere = Object.keys(REGISTRY).filter(id => !ours.has(Number(id)));
    if (differ.length)
        fail(`CRC_EXTRA differs from node-mavlink's for ids ${differ.join(', ')}`);
    console.log(`D. CRC_EXTRA: the ${types.messages.length} decoded types and ${compared} ` +
        `dialect frames agree with node-mavlink's (${onlyHere.length} ids newer than its ` +
        `tables; ${onlyThere.length} of its ids not in ours${onlyThere.length ? ': ' + onlyThere.join(', ') : ''})`);
}

(async () => {
    const types = run(['types'])[0];
    crcExtras(types);
    await ourFramesThere();
    theirFramesHere(types.messages.map(t => t.id));
    if (failures) {
        console.error(`${failures} mismatches`);
        process.exit(1);
    }
    console.log('cross-check with node-mavlink ' +
        require('node-mavlink/package.json').version + ': all agree');
})().catch(e => { console.error(e); process.exit(1); });
