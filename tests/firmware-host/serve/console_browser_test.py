#!/usr/bin/env python3
"""The operator console in headless Chromium against a real `facectl serve`.

Usage: console_browser_test.py FACECTL CONFIG SCREENSHOT_PNG [--chromium PATH]

Starts `FACECTL serve --config CONFIG --listen 127.0.0.1:PORT`, loads the
console, waits for IDLE, clicks ENABLE, waits for RUNNING (after the enable
ramp), plays the first show, saves a screenshot, jogs (JOG, pick neck_pan,
type a target, see through the API that it gets there within its jog range,
type one outside the range and see the server's 422 reason in the jog panel,
End jog back to RUNNING, a hold slider holds a pose again), clicks DISABLE,
waits for IDLE, and fails on any error in the browser's console or on a
command the page sent by itself on load or on entering JOG. Then it checks that a refused command shows the server's {"error"}
text, stops serve with SIGTERM (it must exit 0), sees the page say
"connection lost", starts serve again on the same port and sees the page
reconnect. Exit status 0 when all held.
"""
import argparse
import base64
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.parse
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from devtools_pipe import HeadlessChromium  # noqa: E402

WIDTH, HEIGHT = 1400, 1250


class Failure(Exception):
    pass


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# With --token: serve's environment has it as TOKEN_VARIABLE (the config names
# it in serve.token_env), the page's URL carries it as ?access_token=, and
# this script's own requests send it as a bearer token.
TOKEN_VARIABLE = "FACECTL_CONSOLE_TEST_TOKEN"
token = None


def call(url, body=None, timeout=5, with_token=True):
    """The JSON answer; raises urllib.error.HTTPError on a 4xx/5xx."""
    headers = {"Content-Type": "application/json"} if body is not None else {}
    if token and with_token:
        headers["Authorization"] = "Bearer " + token
    data = json.dumps(body).encode() if body is not None else None
    request = urllib.request.Request(url, data=data, headers=headers, method="POST" if data else "GET")
    with urllib.request.urlopen(request, timeout=timeout) as answer:
        return json.load(answer)


def get_json(url, timeout=2):
    return call(url, timeout=timeout)


def wait_for(what, check, timeout):
    deadline = time.monotonic() + timeout
    last = None
    while time.monotonic() < deadline:
        try:
            last = check()
            if last:
                return last
        except Exception as error:  # not up yet, not rendered yet
            last = error
        time.sleep(0.1)
    raise Failure(f"timed out after {timeout} s waiting for {what} (last: {last!r})")


def page_state(browser):
    return browser.evaluate("document.getElementById('state').textContent")


def wait_for_state(browser, state, timeout):
    seen = []

    def check():
        now = page_state(browser)
        if not seen or seen[-1] != now:
            seen.append(now)
        return now == state
    try:
        wait_for(f"the page to show {state}", check, timeout)
    except Failure as failure:
        raise Failure(f"{failure}; the page showed {' -> '.join(seen)}") from None
    return seen


def browser_errors(browser):
    """Exceptions, console.error/assert calls and failed loads the page logged."""
    errors = []
    for event in browser.events():
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.exceptionThrown":
            details = params["exceptionDetails"]
            errors.append(details.get("exception", {}).get("description") or details.get("text"))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            errors.append(" ".join(str(a.get("value", a.get("description"))) for a in params["args"]))
        elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
            entry = params["entry"]
            errors.append(f"{entry.get('text')} {entry.get('url', '')}".strip())
    return errors


def commands_logged(base):
    """The commands in the event log, as comparable strings (the log outlives serve)."""
    return {json.dumps(e, sort_keys=True) for e in get_json(base + "/api/v1/events?limit=1000")["events"]
            if e.get("kind") == "command"}


def drive_console(browser, base, screenshot):
    browser.attach_to_page()
    for domain in ("Runtime.enable", "Log.enable", "Page.enable"):
        browser.send(domain)
    browser.send("Emulation.setDeviceMetricsOverride",
                 {"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1, "mobile": False})
    page = base + "/" + (f"?access_token={urllib.parse.quote(token)}" if token else "")
    before = commands_logged(base)
    browser.send("Page.navigate", {"url": page})

    wait_for_state(browser, "IDLE", 20)
    wait_for("ENABLE to be clickable", lambda: browser.evaluate(
        "!document.getElementById('enable').disabled"), 5)
    time.sleep(1.0)  # long enough for a page that sends something by itself to have done it
    sent = commands_logged(base) - before
    if sent:
        raise Failure(f"the page sent commands on load: {sent}")

    check_face_mode(browser, base)

    browser.click("#enable")
    seen = wait_for_state(browser, "RUNNING", 15)
    print("after ENABLE the page showed", " -> ".join(seen))
    # Play the first show with its button: the progress bar follows, and the
    # picture shows the face and the plots moving.
    browser.click("#show-list button")
    wait_for("the progress bar to show the playing show", lambda: ":" in browser.evaluate(
        "document.getElementById('show-progress-text').textContent"), 10)
    time.sleep(3.0)  # a few seconds of plot history for the picture
    shot = browser.send("Page.captureScreenshot", {"format": "png"})
    with open(screenshot, "wb") as out:
        out.write(base64.b64decode(shot["data"]))
    print("screenshot:", screenshot)

    drive_jog(browser, base)

    browser.click("#disable")
    seen = wait_for_state(browser, "IDLE", 15)
    print("after DISABLE the page showed", " -> ".join(seen))

    # The jog target typed outside the range was refused on purpose: Chromium
    # logs that 422 as a failed load. Anything else is an error.
    errors = [e for e in browser_errors(browser)
              if not ("status of 422" in e and e.endswith("/api/v1/jog"))]
    if errors:
        raise Failure("the browser's console had errors:\n  " + "\n  ".join(errors))


def check_face_mode(browser, base):
    """The face panel draws the reduced model's points and skin when the server
    has a face geometry, else says it draws the schematic."""
    try:
        points = len(get_json(base + "/api/v1/face/geometry")["landmarks"])
        expected = f"(reduced model: {points} control points"
    except urllib.error.HTTPError as error:
        if error.code != 404:
            raise
        expected = "(schematic from the signals)"
    wait_for(f"the face panel to say {expected}", lambda: browser.evaluate(
        "document.getElementById('face-mode').textContent").startswith(expected), 10)
    print("face panel:", browser.evaluate("document.getElementById('face-mode').textContent"))


def telemetry_frames(base, rate_hz=50):
    """The telemetry stream's events, as dicts, for as long as the caller iterates."""
    headers = {"Authorization": "Bearer " + token} if token else {}
    request = urllib.request.Request(f"{base}/api/v1/telemetry?rate_hz={rate_hz}", headers=headers)
    with urllib.request.urlopen(request, timeout=5) as stream:
        for line in stream:
            if line.startswith(b"data: "):
                yield json.loads(line[len(b"data: "):])


def type_into(browser, selector, text):
    """Types text into an input as a user would (focus, keys, leave it), which fires `change`."""
    browser.evaluate(f"(() => {{ const e = document.querySelector({json.dumps(selector)});"
                     " e.focus(); e.value = ''; })()")
    browser.send("Input.insertText", {"text": text})
    browser.evaluate("document.activeElement.blur()")


def visible(browser, selector):
    """Laid out on the page: a `hidden` that a style overrides does not count."""
    return browser.evaluate(f"(() => {{ const e = document.querySelector({json.dumps(selector)});"
                            " return !!e && e.getClientRects().length > 0; })()")


def jog_error(browser):
    return browser.evaluate(
        "(() => { const e = document.getElementById('jog-error'); return e.hidden ? '' : e.textContent; })()")


def drive_jog(browser, base):
    """RUNNING -> JOG -> one actuator to a target within its jog range, a refusal shown,
    End jog -> RUNNING, and the hold sliders working again."""
    rig = get_json(base + "/api/v1/rig")
    names = [a["name"] for a in rig["actuators"]]
    pan = names.index("neck_pan")
    lo, hi = rig["actuators"][pan]["jog"]["min"], rig["actuators"][pan]["jog"]["max"]
    struts = sorted(a["name"] for a in rig["actuators"] if a["jog"] is None)
    if not struts:
        raise Failure("the rig lists no mandible strut without a jog range")

    wait_for("JOG to be clickable in RUNNING", lambda: browser.evaluate(
        "!document.getElementById('jog-start').disabled"), 5)
    if visible(browser, "#jog-controls") or visible(browser, "#jog-stop"):
        raise Failure("the jog controls or End jog are shown outside JOG")
    before = commands_logged(base)
    browser.click("#jog-start")
    seen = wait_for_state(browser, "JOG", 10)
    print("after JOG the page showed", " -> ".join(seen))
    wait_for("the jog controls and End jog", lambda: visible(browser, "#jog-controls")
             and visible(browser, "#jog-stop") and not visible(browser, "#jog-start"), 5)
    if "JOG" not in browser.evaluate("document.getElementById('jog-mode').textContent"):
        raise Failure("the jog panel does not say that JOG is the mode")
    if not browser.evaluate("[...document.querySelectorAll('#sliders input')].every(i => i.disabled)"):
        raise Failure("the hold-pose sliders are still live in JOG")
    offered = browser.evaluate("[...document.querySelectorAll('#jog-actuator option')]"
                               ".filter(o => o.disabled).map(o => o.textContent.split(' ')[0]).sort()")
    if offered != struts:
        raise Failure(f"the picker greys out {offered}, the rig's struts are {struts}")

    # Each actuator picked: the slider and the number box span its jog range
    # (lip_pucker's is 0..35 deg, narrower than its soft range), in its unit.
    for index, actuator in enumerate(rig["actuators"]):
        if actuator["jog"] is None:
            continue
        shown = browser.evaluate("(() => { const p = document.getElementById('jog-actuator');"
                                 f" p.value = String({index}); p.dispatchEvent(new Event('change'));"
                                 " const s = document.getElementById('jog-slider');"
                                 " const n = document.getElementById('jog-target');"
                                 " return [s.min, s.max, n.min, n.max].map(Number)"
                                 ".concat([document.getElementById('jog-unit').textContent]); })()")
        jog = actuator["jog"]
        if shown != [jog["min"], jog["max"], jog["min"], jog["max"], actuator["unit"]]:
            raise Failure(f"{actuator['name']}: the jog inputs show {shown}, its jog range is "
                          f"{jog['min']}..{jog['max']} {actuator['unit']}")
    browser.evaluate("(() => { const p = document.getElementById('jog-actuator');"
                     f" p.value = String({pan}); p.dispatchEvent(new Event('change')); }})()")
    sent = commands_logged(base) - before
    if any('"jog start"' not in c for c in sent):
        raise Failure(f"the page sent more than the jog start by itself: {sent}")

    frames = telemetry_frames(base)
    try:
        start = next(frames)["measured"][pan]
        target = round(start + 15 if start + 15 <= hi else start - 15, 1)
        type_into(browser, "#jog-target", str(target))
        deadline = time.monotonic() + 10
        closest = abs(start - target)
        for frame in frames:
            command, measured = frame["commands"][pan], frame["measured"][pan]
            if not lo - 1e-6 <= command <= hi + 1e-6 or not lo - 0.5 <= measured <= hi + 0.5:
                raise Failure(f"neck_pan at {measured} (command {command}), outside its jog range {lo}..{hi}")
            closest = min(closest, abs(measured - target))
            if abs(measured - target) < 0.5:
                break
            if time.monotonic() > deadline:
                raise Failure(f"neck_pan went from {start} to {measured} deg, not to the target {target} "
                              f"(closest {closest:.2f}; jog panel: {jog_error(browser)!r})")
    finally:
        frames.close()
    print(f"jogged neck_pan from {start:.1f} to {target} deg")
    wait_for("the jog panel to show the measured position", lambda: abs(float(browser.evaluate(
        "document.getElementById('jog-measured').textContent").split("measured ")[1].split()[0])
        - target) < 1.0, 5)

    # Typed outside the range, the number is sent as it is and the server's reason shown.
    outside = hi + 20
    try:
        call(base + "/api/v1/jog", {"actuator": "neck_pan", "position": outside})
        raise Failure(f"the server accepted neck_pan at {outside}")
    except urllib.error.HTTPError as refusal:
        if refusal.code != 422:
            raise Failure(f"neck_pan at {outside}: {refusal.code}, expected 422") from None
        reason = json.load(refusal)["error"]
    type_into(browser, "#jog-target", str(outside))
    wait_for(f"the jog panel to show the server's reason {reason!r}",
             lambda: reason in jog_error(browser) and "422" in jog_error(browser), 5)

    browser.click("#jog-stop")
    seen = wait_for_state(browser, "RUNNING", 15)
    print("after End jog the page showed", " -> ".join(seen))
    wait_for("JOG back and the jog controls hidden", lambda: visible(browser, "#jog-start")
             and not visible(browser, "#jog-controls"), 5)
    # The hold sliders work again: one moved holds a pose.
    wait_for("the hold sliders to be live again", lambda: browser.evaluate(
        "[...document.querySelectorAll('#sliders input')].every(i => !i.disabled)"), 5)
    browser.evaluate("(() => { const s = document.querySelector('#sliders input');"
                     " s.value = (Number(s.min) + Number(s.max)) / 2; s.dispatchEvent(new Event('input')); })()")
    wait_for("a hold slider to hold a pose", lambda: get_json(base + "/api/v1/state")["source"]["kind"] == "pose", 5)


def check_refusal_shown(browser, base):
    """A command the server refuses: the page shows the server's own {"error"} text."""
    try:
        call(base + "/api/v1/show/play", {"name": "no such show"})
        raise Failure("the server accepted an unknown show")
    except urllib.error.HTTPError as refusal:
        reason = json.load(refusal)["error"]
    browser.evaluate("FaceCtl.ui.command('/api/v1/show/play', {name: 'no such show'})")
    wait_for(f"the page to show the server's reason {reason!r}", lambda: reason in browser.evaluate(
        "(() => { const m = document.getElementById('message'); return m.hidden ? '' : m.textContent; })()"), 5)


def check_token_required(base):
    """With a token configured, the API and the console's files refuse a request without it."""
    for path in ("/api/v1/state", "/", "/console/console.js"):
        try:
            call(base + path, with_token=False)
        except urllib.error.HTTPError as refusal:
            if refusal.code == 401:
                continue
            raise Failure(f"GET {path} without the token: {refusal.code}, expected 401") from None
        raise Failure(f"GET {path} without the token was answered")


def connection_text(browser):
    return browser.evaluate("document.getElementById('connection').textContent")


def start_serve(facectl, config, port, log, work):
    # The event log goes to the XDG state folder: this test's own, not the user's.
    env = dict(os.environ, XDG_STATE_HOME=os.path.join(work, "state"),
               **({TOKEN_VARIABLE: token} if token else {}))
    env.pop("LOGS_DIRECTORY", None)
    return subprocess.Popen([facectl, "serve", "--config", config, "--listen", f"127.0.0.1:{port}"],
                            stdout=log, stderr=subprocess.STDOUT, env=env)


def wait_until_serving(serve, base):
    wait_for("facectl serve to answer",
             lambda: serve.poll() is not None or get_json(base + "/api/v1/state"), 30)
    if serve.poll() is not None:
        raise Failure(f"facectl serve exited {serve.returncode} at start")


def stop_serve(serve):
    serve.send_signal(signal.SIGTERM)
    try:
        code = serve.wait(timeout=15)
    except subprocess.TimeoutExpired:
        raise Failure("facectl serve did not exit within 15 s of SIGTERM") from None
    if code != 0:
        raise Failure(f"facectl serve exited {code} on SIGTERM, expected 0")


def restart_and_reconnect(browser, serve, start):
    """Stops serve; the page must say so; a new serve: the page must come back by itself."""
    stop_serve(serve)
    wait_for("the page to say the connection is lost",
             lambda: "connection lost" in connection_text(browser), 10)
    serve = start()
    wait_for("the page to reconnect", lambda: connection_text(browser) == "connected", 30)
    wait_for_state(browser, "IDLE", 10)
    wait_for("the telemetry stream to come back", lambda: browser.evaluate(
        "document.getElementById('telemetry-status').textContent").startswith("live"), 15)
    print("after a restart of serve the page reconnected")
    return serve


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("facectl")
    parser.add_argument("config")
    parser.add_argument("screenshot")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    parser.add_argument("--token", help=f"serve has this access token (CONFIG names ${TOKEN_VARIABLE})")
    args = parser.parse_args()
    global token
    token = args.token
    if not os.access(args.chromium, os.X_OK):
        print(f"chromium not found at {args.chromium} (scripts/setup.sh installs it)", file=sys.stderr)
        return 1
    os.makedirs(os.path.dirname(os.path.abspath(args.screenshot)), exist_ok=True)

    with tempfile.TemporaryDirectory(prefix="facectl-console-") as work:
        port = free_port()
        base = f"http://127.0.0.1:{port}"
        log_path = os.path.join(work, "serve.log")
        log = open(log_path, "wb")
        serving = []

        def start():
            serving.append(start_serve(args.facectl, args.config, port, log, work))
            wait_until_serving(serving[-1], base)
            return serving[-1]

        browser = None
        try:
            serve = start()
            if token:
                check_token_required(base)
            browser = HeadlessChromium(args.chromium, os.path.join(work, "profile"), WIDTH, HEIGHT)
            drive_console(browser, base, args.screenshot)
            check_refusal_shown(browser, base)
            serve = restart_and_reconnect(browser, serve, start)
            stop_serve(serve)
        except Failure as failure:
            print("FAIL:", failure, file=sys.stderr)
            if browser and browser_errors(browser):
                print("the browser's console:\n  " + "\n  ".join(browser_errors(browser)), file=sys.stderr)
            with open(log_path, errors="replace") as text:
                print("---- facectl serve output ----\n" + text.read()[-4000:], file=sys.stderr)
            return 1
        finally:
            if browser:
                browser.close()
            for process in serving:
                if process.poll() is None:
                    process.kill()
                    process.wait()
            log.close()
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
