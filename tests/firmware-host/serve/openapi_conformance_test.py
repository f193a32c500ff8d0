#!/usr/bin/env python3
"""`facectl serve` against docs/openapi.yaml, both ways.

    openapi_conformance_test.py FACECTL SOURCE_DIR [OPENAPI_YAML]

Checks the document's structure (OpenAPI 3.0.3; Debian 12 has no
python3-openapi-spec-validator, so the checks are our own), then starts
`facectl serve` on the shipped config and a free loopback port and sends a
request to every operation the document lists: each answer's status must be
one the document lists for that operation and the one this test expects, and
every JSON answer (and telemetry event) must validate against the documented
schema, with objects closed (a field the server sends that the document lacks
fails). The harmless requests sent are also checked against the documented
request schemas and parameters. Conversely every route `s.Get(`/`s.Post(` of
firmware-host/serve/http_api.cpp must be documented. A second run with an
access token checks the 401s and both ways of sending the token. SIGTERM must
then stop each server with exit status 0.

Needs python3-yaml and python3-jsonschema (Debian 12; scripts/setup.sh must
install python3-jsonschema). OPENAPI_YAML (default SOURCE_DIR/docs/openapi.yaml)
lets a changed copy of the document be checked, to see the test fail.
"""

import copy
import http.client
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse

import jsonschema  # python3-jsonschema
import yaml  # python3-yaml

HTTP_METHODS = ("get", "put", "post", "delete", "options", "head", "patch", "trace")
TOKEN_ENV = "FACECTL_OPENAPI_TEST_TOKEN"
TOKEN = "openapi-conformance-token-0123456789"

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL: " + msg, flush=True)


# ---- the document ---------------------------------------------------------


def resolve(doc, node):
    """Follows a local $ref (one level at a time) until a non-$ref node."""
    seen = set()
    while isinstance(node, dict) and "$ref" in node:
        ref = node["$ref"]
        if not ref.startswith("#/") or ref in seen:
            raise ValueError("unsupported or circular $ref " + ref)
        seen.add(ref)
        target = doc
        for part in ref[2:].split("/"):
            part = part.replace("~1", "/").replace("~0", "~")
            if not isinstance(target, dict) or part not in target:
                raise ValueError("unresolved $ref " + ref)
            target = target[part]
        node = target
    return node


def to_json_schema(doc, schema, strict):
    """An OpenAPI 3.0 schema object as a self-contained draft-4 JSON Schema:
    $refs inlined, `nullable` as a null alternative; with `strict`, objects
    with `properties` and no `additionalProperties` are closed."""
    schema = resolve(doc, schema)
    if isinstance(schema, list):
        return [to_json_schema(doc, s, strict) for s in schema]
    if not isinstance(schema, dict):
        return schema
    out = {}
    for key, value in schema.items():
        if key in ("properties", "definitions", "patternProperties"):
            out[key] = {k: to_json_schema(doc, v, strict) for k, v in value.items()}
        elif key in ("items", "additionalProperties", "not") and isinstance(value, dict):
            out[key] = to_json_schema(doc, value, strict)
        elif key in ("allOf", "anyOf", "oneOf"):
            out[key] = [to_json_schema(doc, v, strict) for v in value]
        elif key in ("nullable", "example", "externalDocs", "xml", "deprecated", "readOnly",
                     "writeOnly", "discriminator") or key.startswith("x-"):
            continue
        else:
            out[key] = copy.deepcopy(value)
    if schema.get("nullable"):
        if "type" in out:
            out["type"] = [out["type"], "null"]
        if "enum" in out:
            out["enum"] = list(out["enum"]) + [None]
    if strict and "properties" in out and "additionalProperties" not in out:
        out["additionalProperties"] = False
    return out


def walk_refs(node, where, doc):
    if isinstance(node, dict):
        if "$ref" in node:
            try:
                resolve(doc, node)
            except ValueError as e:
                fail("%s: %s" % (where, e))
        for k, v in node.items():
            walk_refs(v, where + "/" + str(k), doc)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            walk_refs(v, "%s/%d" % (where, i), doc)


def check_schema(doc, schema, where):
    try:
        jsonschema.Draft4Validator.check_schema(to_json_schema(doc, schema, False))
    except (jsonschema.SchemaError, ValueError) as e:
        fail("%s: not a valid schema: %s" % (where, getattr(e, "message", e)))


def structural_check(doc):
    """What openapi-spec-validator would catch first, for the subset used here."""
    if doc.get("openapi") != "3.0.3":
        fail("openapi: expected 3.0.3, found %r" % doc.get("openapi"))
    info = doc.get("info") or {}
    for key in ("title", "version"):
        if not isinstance(info.get(key), str):
            fail("info.%s: expected a string" % key)
    if not isinstance(doc.get("paths"), dict) or not doc["paths"]:
        fail("paths: expected a non-empty mapping")
        return
    walk_refs(doc, "#", doc)
    schemes = doc.get("components", {}).get("securitySchemes", {})
    for name, scheme in schemes.items():
        if scheme.get("type") == "http" and scheme.get("scheme") != "bearer":
            fail("securitySchemes.%s: expected the bearer scheme" % name)
        if scheme.get("type") == "apiKey" and (scheme.get("in"), scheme.get("name")) != (
                "query", "access_token"):
            fail("securitySchemes.%s: expected the access_token query parameter" % name)
    security = doc.get("security")
    if not isinstance(security, list) or {} not in security:
        fail("security: expected a list with the empty alternative (no token configured)")
    else:
        for req in security:
            for name in req:
                if name not in schemes:
                    fail("security: no securityScheme %r" % name)
        for kind in ("http", "apiKey"):
            if not any(schemes.get(n, {}).get("type") == kind for r in security for n in r):
                fail("security: no %s scheme applies globally" % kind)
    for name, schema in doc.get("components", {}).get("schemas", {}).items():
        check_schema(doc, schema, "components.schemas." + name)
    op_ids = set()
    for path, item in doc["paths"].items():
        if not path.startswith("/"):
            fail("paths.%s: expected a leading /" % path)
        for method, op in item.items():
            if method not in HTTP_METHODS:
                if method not in ("summary", "description", "parameters", "servers"):
                    fail("paths.%s: unknown key %s" % (path, method))
                continue
            where = "%s %s" % (method.upper(), path)
            if op.get("operationId") in op_ids:
                fail("%s: operationId %s is not unique" % (where, op.get("operationId")))
            op_ids.add(op.get("operationId"))
            responses = op.get("responses")
            if not isinstance(responses, dict) or not responses:
                fail(where + ": no responses")
                continue
            for status, resp in responses.items():
                if not re.fullmatch(r"[1-5][0-9][0-9]", str(status)):
                    fail("%s: response key %r is not a quoted status code" % (where, status))
                resp = resolve(doc, resp)
                if not isinstance(resp.get("description"), str):
                    fail("%s %s: a response needs a description" % (where, status))
                for ctype, media in (resp.get("content") or {}).items():
                    if "schema" in media:
                        check_schema(doc, media["schema"], "%s %s %s" % (where, status, ctype))
                    else:
                        fail("%s %s %s: no schema" % (where, status, ctype))
                if str(status).startswith("4") or str(status).startswith("5"):
                    content = resp.get("content") or {}
                    if "application/json" not in content or resolve(
                            doc, content["application/json"]["schema"]) is not resolve(
                                doc, {"$ref": "#/components/schemas/Error"}):
                        fail("%s %s: expected the Error schema" % (where, status))
            if "401" not in responses:
                fail(where + ": every operation can answer 401 when a token is configured")
            if "403" not in responses:
                fail(where + ": every operation can answer 403 to a foreign page without a token")
            for p in op.get("parameters", []):
                p = resolve(doc, p)
                if p.get("in") not in ("query", "header", "path", "cookie") or "name" not in p:
                    fail("%s: parameter needs name and in" % where)
                if "schema" in p:
                    check_schema(doc, p["schema"], "%s parameter %s" % (where, p.get("name")))
            if "requestBody" in op:
                body = resolve(doc, op["requestBody"])
                if "content" not in body:
                    fail(where + ": requestBody needs content")
                for ctype, media in body.get("content", {}).items():
                    check_schema(doc, media.get("schema", {}), "%s request %s" % (where, ctype))


def documented_operations(doc):
    return {(m.upper(), p): op for p, item in doc["paths"].items() for m, op in item.items()
            if m in HTTP_METHODS}


def routes_in_code(source_dir):
    """The routes http_api.cpp registers: ("GET"|"POST", path)."""
    with open(os.path.join(source_dir, "firmware-host/serve/http_api.cpp")) as f:
        code = f.read()
    routes = {(m.upper(), p) for m, p in re.findall(r'\bs\.(Get|Post|Put|Delete|Patch|Options)'
                                                    r'\(\s*"([^"]*)"', code)}
    for mount in re.findall(r'set_mount_point\(\s*"([^"]*)"', code):
        routes.add(("GET", mount))
    return routes


# ---- the server ------------------------------------------------------------


class Server:
    def __init__(self, facectl, config, tmpdir, env=None):
        self.lines = []
        self.port = None
        got_port = threading.Event()
        self.proc = subprocess.Popen(
            [facectl, "serve", "--config", config, "--listen", "127.0.0.1:0", "--event-log",
             os.path.join(tmpdir, "events.jsonl")],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            env=env, text=True)

        def drain():
            for line in self.proc.stderr:
                self.lines.append(line.rstrip("\n"))
                m = re.search(r"listening on http://127\.0\.0\.1:(\d+)/", line)
                if m and self.port is None:
                    self.port = int(m.group(1))
                    got_port.set()
            got_port.set()

        self.reader = threading.Thread(target=drain, daemon=True)
        self.reader.start()
        if not got_port.wait(60) or self.port is None:
            self.proc.kill()
            raise SystemExit("facectl serve did not say where it listens:\n" +
                             "\n".join(self.lines[-20:]))

    def stop(self):
        """SIGTERM; the exit status (None if it had to be killed)."""
        self.proc.send_signal(signal.SIGTERM)
        try:
            rc = self.proc.wait(30)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
            rc = None
        self.reader.join(5)
        return rc


# 60 s: the first GET /api/v1/rig proves the jog ranges (docs/API.md), which takes tens
# of seconds in a sanitizer build.
def request(port, method, path, query=None, body=None, headers=None, timeout=60):
    """(status, content type, headers, body bytes); `body` bytes or a JSON value."""
    url = path + ("?" + urllib.parse.urlencode(query) if query else "")
    if body is not None and not isinstance(body, bytes):
        body = json.dumps(body).encode()
    if body is None and method == "POST":
        body = b""  # Content-Length: 0 (`curl -d ''`)
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout)
    try:
        conn.request(method, url, body=body, headers=headers or {})
        resp = conn.getresponse()
        data = resp.read()
        return resp.status, resp.getheader("Content-Type", ""), resp.headers, data
    finally:
        conn.close()


def open_stream(port, query=None, timeout=15):
    url = "/api/v1/telemetry" + ("?" + urllib.parse.urlencode(query) if query else "")
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout)
    conn.request("GET", url)
    return conn, conn.getresponse()


def read_events(resp, count):
    buf = b""
    events = []
    deadline = time.monotonic() + 10
    while len(events) < count and time.monotonic() < deadline:
        chunk = resp.read1(65536)
        if not chunk:
            break
        buf += chunk
        while b"\n\n" in buf:
            raw, buf = buf.split(b"\n\n", 1)
            events.append(raw.decode())
    return events


# ---- checks against the document --------------------------------------------


class Checker:
    def __init__(self, doc):
        self.doc = doc
        self.ops = documented_operations(doc)
        self.exercised = set()

    def op(self, method, path):
        return self.ops.get((method, path))

    def check_request(self, method, path, query, body, valid):
        """The test's own request against the documented request: `valid` says
        whether it should conform (a harmless request) or not (a bad field)."""
        op = self.op(method, path)
        if op is None:
            return
        errors = []
        params = {resolve(self.doc, p)["name"]: resolve(self.doc, p)
                  for p in op.get("parameters", [])}
        schemes = self.doc.get("components", {}).get("securitySchemes", {}).values()
        token_params = {s["name"] for s in schemes if s.get("type") == "apiKey" and
                        s.get("in") == "query"}
        for name, text in (query or {}).items():
            if name in token_params:
                continue
            if name not in params:
                fail("%s %s: sends query parameter %s the document lacks" % (method, path, name))
                continue
            schema = to_json_schema(self.doc, params[name]["schema"], False)
            try:
                value = int(text) if schema.get("type") == "integer" else float(text)
            except ValueError:
                errors.append("%s=%r is not a %s" % (name, text, schema.get("type")))
                continue
            errors += [e.message for e in jsonschema.Draft4Validator(schema).iter_errors(value)]
        if body is not None and not isinstance(body, bytes):
            rb = op.get("requestBody")
            if rb is None:
                fail("%s %s: sends a body the document does not describe" % (method, path))
            else:
                schema = resolve(self.doc, rb)["content"]["application/json"]["schema"]
                schema = to_json_schema(self.doc, schema, False)
                errors += [e.message for e in jsonschema.Draft4Validator(schema).iter_errors(body)]
        if valid and errors:
            fail("%s %s %r %r: a request the server takes, but the document rejects it: %s" %
                 (method, path, query, body, "; ".join(errors)))
        if not valid and not errors:
            fail("%s %s %r %r: a request the server refuses as malformed, but the document "
                 "admits it" % (method, path, query, body))

    def check_response(self, method, path, status, ctype, data, expect):
        """The answer's status is documented (and expected); a JSON body validates."""
        what = "%s %s -> %d" % (method, path, status)
        op = self.op(method, path)
        if op is None:
            fail("%s: the operation is not documented" % what)
            return None
        self.exercised.add((method, path))
        if status != expect:
            fail("%s: expected %d (%s)" % (what, expect, data[:200]))
        resp = op["responses"].get(str(status))
        if resp is None:
            fail("%s: status not documented (documented: %s)" %
                 (what, ", ".join(sorted(op["responses"]))))
            return None
        content = resolve(self.doc, resp).get("content") or {}
        media_type = ctype.split(";")[0].strip()
        if media_type not in content:
            fail("%s: answers %s, documented: %s" % (what, media_type, ", ".join(content)))
            return None
        if media_type != "application/json":
            return None
        try:
            value = json.loads(data)
        except ValueError:
            fail("%s: not JSON: %r" % (what, data[:200]))
            return None
        self.validate(what, content[media_type]["schema"], value)
        return value

    def validate(self, what, schema, value):
        schema = to_json_schema(self.doc, schema, True)
        for e in sorted(jsonschema.Draft4Validator(schema).iter_errors(value), key=str):
            fail("%s: at %s: %s" % (what, "/".join(map(str, e.absolute_path)) or "(root)",
                                    e.message))


def call(chk, port, method, path, expect, query=None, body=None, valid=True, headers=None):
    chk.check_request(method, path, query, body, valid)
    status, ctype, _, data = request(port, method, path, query, body, headers)
    return chk.check_response(method, path, status, ctype, data, expect)


def wait_state(port, wanted, seconds):
    deadline = time.monotonic() + seconds
    state = None
    while time.monotonic() < deadline:
        _, _, _, data = request(port, "GET", "/api/v1/state")
        state = json.loads(data)["state"]
        if state in wanted:
            break
        time.sleep(0.05)
    return state


def exercise(chk, port):
    """A request to every documented operation, in an order that leaves the head IDLE."""
    call(chk, port, "GET", "/api/v1/state", 200)
    rig = call(chk, port, "GET", "/api/v1/rig", 200)
    geometry = call(chk, port, "GET", "/api/v1/face/geometry", 200)
    call(chk, port, "GET", "/api/v1/shows", 200)
    expressions = call(chk, port, "GET", "/api/v1/expressions", 200)
    call(chk, port, "GET", "/api/v1/events", 200)
    call(chk, port, "GET", "/api/v1/events", 200, query={"limit": "5"})
    call(chk, port, "GET", "/api/v1/events", 400, query={"limit": "0"}, valid=False)
    call(chk, port, "GET", "/api/v1/events", 400, query={"limit": "many"}, valid=False)

    call(chk, port, "POST", "/api/v1/reset", 409, body={})  # IDLE: nothing to reset
    call(chk, port, "POST", "/api/v1/reset", 400, body={"enable": "yes"}, valid=False)

    for op in ("play", "queue"):
        call(chk, port, "POST", "/api/v1/show/" + op, 404, body={"name": "no-such-show"})
    call(chk, port, "POST", "/api/v1/show/play", 400, body={}, valid=False)
    call(chk, port, "POST", "/api/v1/show/play", 400, body=b'{"name": ')
    call(chk, port, "POST", "/api/v1/show/stop", 200)
    call(chk, port, "POST", "/api/v1/show/stop", 400, body=b"{")
    call(chk, port, "POST", "/api/v1/show/stop", 413, body=b" " * (65 * 1024))

    names = (expressions or {}).get("expressions") or ["joy"]
    call(chk, port, "POST", "/api/v1/expression/hold", 200, body={"name": names[0], "weight": 0.5})
    call(chk, port, "POST", "/api/v1/expression/hold", 404, body={"name": "no-such-expression"})
    call(chk, port, "POST", "/api/v1/expression/hold", 422, body={"name": names[0], "weight": 2},
         valid=False)
    call(chk, port, "POST", "/api/v1/expression/hold", 400,
         body={"name": names[0], "weight": "1"}, valid=False)

    sig = (rig or {}).get("signals", [{"key": "jaw_pitch_deg", "max": 18.0}])[0]
    call(chk, port, "POST", "/api/v1/pose", 422, body={"signals": {sig["key"]: sig["max"] + 1}})
    call(chk, port, "POST", "/api/v1/pose", 422, body={"signals": {"no_such_signal": 0}})
    call(chk, port, "POST", "/api/v1/pose", 200, body={"signals": {sig["key"]: sig["max"]}})
    call(chk, port, "POST", "/api/v1/show/stop", 200)  # back to neutral

    call(chk, port, "GET", "/api/v1/telemetry", 400, query={"rate_hz": "5"}, valid=False)
    call(chk, port, "GET", "/api/v1/telemetry", 400, query={"rate_hz": "101"}, valid=False)
    check_telemetry(chk, port, rig, geometry)

    call(chk, port, "GET", "/", 404 if not console_present(port) else 200)
    call(chk, port, "GET", "/console/", 404 if not console_present(port) else 200)

    call(chk, port, "POST", "/api/v1/pose", 400, body=b"{")
    call(chk, port, "POST", "/api/v1/jog/start", 409)  # IDLE
    call(chk, port, "POST", "/api/v1/jog/stop", 409)
    call(chk, port, "POST", "/api/v1/jog", 400, body={"actuator": "x"}, valid=False)
    call(chk, port, "POST", "/api/v1/jog", 404, body={"actuator": "no-such-actuator", "position": 0})
    actuators = (rig or {}).get("actuators") or []
    call(chk, port, "POST", "/api/v1/jog", 409,
         body={"actuator": actuators[-1]["name"], "position": actuators[-1]["soft_min"]})

    call(chk, port, "POST", "/api/v1/enable", 200)
    if wait_state(port, ("RUNNING", "FAULT", "ESTOP"), 10) != "RUNNING":
        print("note: the head did not reach RUNNING (a loaded machine?)", flush=True)
    else:
        call(chk, port, "POST", "/api/v1/jog/start", 200)
        if wait_state(port, ("JOG", "FAULT", "ESTOP"), 5) == "JOG":
            a = actuators[-1]
            call(chk, port, "POST", "/api/v1/jog", 422,
                 body={"actuator": a["name"], "position": a["soft_max"] + 1})
            call(chk, port, "POST", "/api/v1/jog", 200,
                 body={"actuator": a["name"], "position": (a["soft_min"] + a["soft_max"]) / 2})
            call(chk, port, "POST", "/api/v1/jog/stop", 200)
            wait_state(port, ("RUNNING", "FAULT", "ESTOP"), 5)
    call(chk, port, "POST", "/api/v1/disable", 200)
    end = wait_state(port, ("IDLE", "FAULT", "ESTOP"), 10)
    if end in ("FAULT", "ESTOP"):
        # Overruns on a loaded machine fault the loop: then reset is a 200.
        print("note: the head faulted (%s); resetting it" % end, flush=True)
        call(chk, port, "POST", "/api/v1/reset", 200, body={"enable": False})
        wait_state(port, ("IDLE",), 10)

    # Not an operation: an unknown path answers the Error schema.
    status, _, _, data = request(port, "GET", "/api/v1/no-such-thing")
    if status != 404:
        fail("GET /api/v1/no-such-thing -> %d: expected 404" % status)
    chk.validate("GET /api/v1/no-such-thing", {"$ref": "#/components/schemas/Error"},
                 json.loads(data))


def console_present(port):
    status, _, _, _ = request(port, "GET", "/")
    return status == 200


def check_telemetry(chk, port, rig, geometry):
    method, path = "GET", "/api/v1/telemetry"
    query = {"rate_hz": "50"}
    chk.check_request(method, path, query, None, True)
    conn, resp = open_stream(port, query)
    try:
        chk.check_response(method, path, resp.status, resp.getheader("Content-Type", ""), b"",
                           200)
        events = read_events(resp, 3)
    finally:
        conn.close()
    if len(events) < 3:
        fail("telemetry: expected 3 events, got %d" % len(events))
    media = resolve(chk.doc, chk.op(method, path)["responses"]["200"])["content"][
        "text/event-stream"]
    schema = media.get("x-event-data")
    if schema is None:
        fail("telemetry: the text/event-stream media type names no x-event-data schema")
        return
    for raw in events:
        if not raw.startswith("data: ") or "\n" in raw:
            fail("telemetry: expected one `data: ` line per event, found %r" % raw[:80])
            continue
        event = json.loads(raw[len("data: "):])
        chk.validate("telemetry event", schema, event)
        if rig:
            for key, of in (("commands", "actuators"), ("measured", "actuators"),
                            ("face", "signals")):
                if len(event.get(key, [])) != len(rig[of]):
                    fail("telemetry: %s has %d values, the rig %d %s" %
                         (key, len(event.get(key, [])), len(rig[of]), of))
        if geometry and len(event.get("landmarks_mm", [])) != 3 * len(geometry["landmarks"]):
            fail("telemetry: landmarks_mm has %d values, expected 3 per geometry landmark (%d)" %
                 (len(event.get("landmarks_mm", [])), len(geometry["landmarks"])))

    # Open streams until one is refused (serve.max_streams is 1..64).
    streams = []
    try:
        for _ in range(65):
            conn, resp = open_stream(port, {"rate_hz": "10"})
            if resp.status != 200:
                chk.check_response(method, path, resp.status, resp.getheader("Content-Type", ""),
                                   resp.read(), 503)
                conn.close()
                break
            streams.append(conn)
        else:
            fail("telemetry: 65 streams open and none refused")
    finally:
        for conn in streams:
            conn.close()
    print("telemetry: the stream after %d open ones was refused" % len(streams), flush=True)


def check_foreign_pages(chk, port):
    """Without a token, every operation refuses what another web page could send."""
    for method, path in sorted(chk.ops):
        body = b"" if method == "POST" else None
        for headers in ({"Origin": "http://attacker.example"}, {"Host": "attacker.example"}):
            status, ctype, _, data = request(port, method, path, None, body, headers)
            chk.check_response(method, path, status, ctype, data, 403)
    call(chk, port, "GET", "/api/v1/state", 200,
         headers={"Origin": "http://127.0.0.1:%d" % port})
    print("foreign pages: %d operations answer 403" % len(chk.ops), flush=True)


def check_token(chk, port):
    """With a token configured every operation needs it; header or query parameter."""
    for method, path in sorted(chk.ops):
        body = b"" if method == "POST" else None
        for headers, query in (({}, None), ({"Authorization": "Bearer wrong-token-0123456789"},
                                            None), ({}, {"access_token": "wrong"})):
            status, ctype, hdrs, data = request(port, method, path, query, body, headers)
            chk.check_response(method, path, status, ctype, data, 401)
            if status == 401 and hdrs.get("WWW-Authenticate") != 'Bearer realm="facectl"':
                fail("%s %s -> 401 without WWW-Authenticate: Bearer realm=\"facectl\"" %
                     (method, path))
    call(chk, port, "GET", "/api/v1/state", 200, headers={"Authorization": "Bearer " + TOKEN})
    call(chk, port, "GET", "/api/v1/state", 200, query={"access_token": TOKEN})
    auth = {"Authorization": "Bearer " + TOKEN}
    call(chk, port, "POST", "/api/v1/show/play", 404, body={"name": "no-such-show"}, headers=auth)
    # This run's shows folder holds a show that does not load.
    shows = call(chk, port, "GET", "/api/v1/shows", 200, headers=auth)
    if not any(s.get("name") == "broken" and "error" in s for s in (shows or {}).get("shows", [])):
        fail("GET /api/v1/shows: expected the show 'broken' listed with an error: %r" % shows)
    call(chk, port, "POST", "/api/v1/show/queue", 422, body={"name": "broken"}, headers=auth)
    print("token: %d operations answer 401 without it, 200 with it" % len(chk.ops), flush=True)


def token_config(source_dir, tmpdir):
    """The shipped runtime file with absolute paths, serve.token_env, and a
    shows folder with a show that does not load."""
    config_dir = os.path.join(source_dir, "config")
    with open(os.path.join(config_dir, "facectl.yaml")) as f:
        text = f.read()

    def absolute(m):
        return "%s: %s" % (m.group(1), os.path.join(config_dir, m.group(2)))

    text = re.sub(r"(?m)^(head|rig|expressions|show): *([^\s#/][^\s#]*)", absolute, text)
    shows = os.path.join(tmpdir, "shows")
    os.mkdir(shows)
    with open(os.path.join(shows, "broken.yaml"), "w") as f:
        f.write("this: [is not a show\n")
    serve = "serve:\n  token_env: %s\n  shows: %s" % (TOKEN_ENV, shows)
    text = re.sub(r"(?m)^[ \t]+(token_env|token_file|shows):.*\n", "", text)
    if re.search(r"(?m)^serve:[ \t]*(#.*)?$", text):
        text = re.sub(r"(?m)^serve:[ \t]*(#.*)?$", serve, text, count=1)
    else:
        text += "\n" + serve + "\n"
    path = os.path.join(tmpdir, "facectl.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


def main():
    if len(sys.argv) not in (3, 4):
        raise SystemExit(__doc__)
    facectl, source_dir = sys.argv[1], os.path.abspath(sys.argv[2])
    doc_path = sys.argv[3] if len(sys.argv) == 4 else os.path.join(source_dir, "docs/openapi.yaml")
    with open(doc_path) as f:
        doc = yaml.safe_load(f)

    structural_check(doc)
    if failures:
        raise SystemExit("%s: %d structural problem(s)" % (doc_path, len(failures)))
    chk = Checker(doc)

    # Both ways between the document and http_api.cpp.
    code = routes_in_code(source_dir)
    if not code:
        fail("no routes found in http_api.cpp (has the registration changed?)")
    for method, path in sorted(code - set(chk.ops)):
        fail("%s %s: served (http_api.cpp) but not documented" % (method, path))
    for method, path in sorted(set(chk.ops) - code):
        fail("%s %s: documented but not served (http_api.cpp)" % (method, path))

    with tempfile.TemporaryDirectory(prefix="facectl-openapi-") as tmp:
        server = Server(facectl, os.path.join(source_dir, "config/facectl.yaml"), tmp)
        try:
            exercise(chk, server.port)
            check_foreign_pages(chk, server.port)
        finally:
            rc = server.stop()
        if rc != 0:
            fail("facectl serve: SIGTERM: exit status %s, expected 0\n%s" %
                 (rc, "\n".join(server.lines[-15:])))
        for method, path in sorted(set(chk.ops) - chk.exercised):
            fail("%s %s: documented, but this test sends it no request" % (method, path))

        token_dir = os.path.join(tmp, "token")
        os.mkdir(token_dir)
        env = dict(os.environ, **{TOKEN_ENV: TOKEN})
        server = Server(facectl, token_config(source_dir, token_dir), token_dir, env)
        try:
            check_token(chk, server.port)
        finally:
            rc = server.stop()
        if rc != 0:
            fail("facectl serve (token): SIGTERM: exit status %s, expected 0\n%s" %
                 (rc, "\n".join(server.lines[-15:])))

    if failures:
        print("%d failure(s) against %s" % (len(failures), doc_path))
        return 1
    print("facectl serve conforms to %s: %d operations" % (doc_path, len(chk.ops)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
