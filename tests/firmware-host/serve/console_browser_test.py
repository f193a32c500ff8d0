#!/usr/bin/env python3
"""The operator console in headless Chromium against a real `facectl serve`.

Usage: console_browser_test.py FACECTL CONFIG SCREENSHOT_PNG [--chromium PATH]

Starts `FACECTL serve --config CONFIG --listen 127.0.0.1:PORT`, loads the
console, waits for IDLE, clicks ENABLE, waits for RUNNING (after the enable
ramp), plays the first show, saves a screenshot, clicks DISABLE, waits for IDLE, and fails on any
error in the browser's console or on a command the page sent by itself on
load. Then it checks that a refused command shows the server's {"error"}
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

    browser.click("#disable")
    seen = wait_for_state(browser, "IDLE", 15)
    print("after DISABLE the page showed", " -> ".join(seen))

    errors = browser_errors(browser)
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
