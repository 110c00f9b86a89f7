#!/usr/bin/python3
"""The dashboard in a real browser: headless Chromium (Debian's chromium, chromium-driver and
python3-selenium) against a real coordinator with TLS and tokens on 127.0.0.1, one worker and a
submitted job. Logs in, sees the job listed and its image change between two epochs, reads the
error plot's points and checks them against the JSON endpoint, cancels the job and sees its state
change, and looks at the workers page. A screenshot of each page goes to OUT_DIR.

Usage: dashboard_browser_test.py SOURCE_DIR PHOTONFARM COORDINATOR WORKER OUT_DIR
Exit 77 (CTest's skip) without Chromium or Selenium, unless CI=true (then it fails)."""
import json
import os
import re
import shutil
import ssl
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request

TIMEOUT = 90  # seconds any one thing may take before the test fails


def skip_or_fail(reason):
    if os.environ.get("CI") == "true":
        print(f"FAILED: {reason} (CI=true: a prerequisite a test would skip for must be present)")
        sys.exit(1)
    print(f"SKIPPED: {reason}")
    sys.exit(77)


try:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait
except ImportError:
    skip_or_fail("python3-selenium is not installed (deploy/install-deps.sh installs it)")
for tool in ("chromium", "chromedriver"):
    if shutil.which(tool) is None:
        skip_or_fail(f"{tool} is not installed (packages chromium, chromium-driver)")


def start(command):
    """A process whose output (stdout and stderr) a thread reads into process.lines, so that a
    full pipe never blocks it."""
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    process.lines = []
    process.changed = threading.Condition()

    def drain():
        for line in process.stdout:
            with process.changed:
                process.lines.append(line)
                process.changed.notify_all()
        with process.changed:
            process.lines.append(None)  # the end
            process.changed.notify_all()

    threading.Thread(target=drain, daemon=True).start()
    return process


def read_until(process, pattern):
    """The first match of `pattern` in a line of the process's output."""
    deadline = time.monotonic() + TIMEOUT
    with process.changed:
        while True:
            for line in process.lines:
                if line is None:
                    raise RuntimeError("process ended before printing %r:\n%s"
                                       % (pattern, "".join(process.lines[:-1])))
                match = re.search(pattern, line)
                if match:
                    return match
            if not process.changed.wait(timeout=max(0, deadline - time.monotonic())):
                raise RuntimeError("no %r within %d s:\n%s"
                                   % (pattern, TIMEOUT, "".join(l for l in process.lines if l)))


def wait_for(driver, condition, what):
    return WebDriverWait(driver, TIMEOUT, poll_frequency=0.1).until(
        lambda d: condition(d), message=f"timed out waiting for {what}")


def main():
    source_dir, photonfarm, coordinator_binary, worker_binary, out_dir = sys.argv[1:6]
    os.makedirs(out_dir, exist_ok=True)
    work = tempfile.mkdtemp(prefix="pf-dashboard-")
    processes = []
    driver = None
    try:
        subprocess.run(["bash", f"{source_dir}/deploy/make-certs.sh", f"{work}/certs"], check=True,
                       stdout=subprocess.DEVNULL)
        certs = f"{work}/certs"
        client_token = open(f"{certs}/client-token").read().strip()
        coordinator = start([coordinator_binary, "--listen", "127.0.0.1:0", "--web-listen", "127.0.0.1:0",
                             "--tls-cert", f"{certs}/coordinator.pem", "--tls-key", f"{certs}/coordinator.key",
                             "--client-token-file", f"{certs}/client-tokens",
                             "--worker-token-file", f"{certs}/worker-tokens"])
        processes.append(coordinator)
        grpc_port = read_until(coordinator, r"listening on 127\.0\.0\.1:(\d+)").group(1)
        url = read_until(coordinator, r"dashboard on (https://\S+)").group(1)
        server = f"127.0.0.1:{grpc_port}"
        worker = start([worker_binary, "--coordinator", server, "--threads", "1",
                        "--tls-ca", f"{certs}/ca.pem", "--token-file", f"{certs}/worker-token"])
        processes.append(worker)
        submitted = subprocess.run(
            [photonfarm, "submit", f"{source_dir}/scenes/cornell-box.gltf", "--server", server,
             "--tls-ca", f"{certs}/ca.pem", "--token-file", f"{certs}/client-token",
             "--name", "browser-test", "--width", "96", "--height", "96", "--photons-per-batch", "20000",
             "--batches-per-epoch", "2", "--until-cancelled"],
            check=True, capture_output=True, text=True)
        job_id = submitted.stdout.strip().splitlines()[-1]
        print(f"coordinator {server}, dashboard {url}, job {job_id}")

        # The JSON endpoint, read with the token as a script would (the CA verifies the server).
        context = ssl.create_default_context(cafile=f"{certs}/ca.pem")

        def api(path):
            request = urllib.request.Request(url.rstrip("/") + path,
                                             headers={"Authorization": f"Bearer {client_token}"})
            with urllib.request.urlopen(request, context=context, timeout=TIMEOUT) as response:
                return json.load(response)

        options = webdriver.ChromeOptions()
        options.binary_location = shutil.which("chromium")
        for argument in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--disable-gpu",
                         "--window-size=1400,1000", f"--user-data-dir={work}/chromium"):
            options.add_argument(argument)
        options.accept_insecure_certs = True  # the test's own CA is not in Chromium's store
        driver = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=options)
        driver.set_page_load_timeout(TIMEOUT)

        # Logging in.
        driver.get(url)
        wait_for(driver, lambda d: d.find_element(By.ID, "login-view").is_displayed(), "the login form")
        driver.save_screenshot(f"{out_dir}/login.png")
        driver.find_element(By.ID, "token").send_keys("not-a-token")
        driver.find_element(By.ID, "login").click()
        wait_for(driver, lambda d: d.find_element(By.ID, "error").is_displayed(), "a refused login")
        assert "not valid" in driver.find_element(By.ID, "error").text, driver.find_element(By.ID, "error").text
        driver.find_element(By.ID, "token").clear()
        driver.find_element(By.ID, "token").send_keys(client_token)
        driver.find_element(By.ID, "login").click()

        # The job list.
        row = f"#jobs tr[data-job-id='{job_id}']"
        wait_for(driver, lambda d: d.find_elements(By.CSS_SELECTOR, row), "the job in the list")
        cells = [c.text for c in driver.find_elements(By.CSS_SELECTOR, row + " td")]
        assert cells[1] == "browser-test" and cells[2] == "RUNNING" and cells[3] == "ppm", cells
        assert cells[11] == "client-1", f"the client's token name, not {cells[11]!r}"
        cookie = driver.get_cookie("pf_session")
        assert cookie and cookie["httpOnly"] and cookie["secure"], cookie
        driver.save_screenshot(f"{out_dir}/jobs.png")

        # The job page: the image changes between two epochs.
        driver.find_element(By.CSS_SELECTOR, row + " a").click()
        wait_for(driver, lambda d: d.find_element(By.ID, "job-view").is_displayed(), "the job's page")

        def loaded_epoch(d):
            """The epoch of the image shown, once it has loaded; its pixels' sum."""
            return d.execute_script("""
                const image = document.getElementById('job-image');
                if (!image.complete || !image.naturalWidth || !image.dataset.epoch) return null;
                const canvas = document.createElement('canvas');
                canvas.width = image.naturalWidth; canvas.height = image.naturalHeight;
                const context = canvas.getContext('2d');
                context.drawImage(image, 0, 0);
                const pixels = context.getImageData(0, 0, canvas.width, canvas.height).data;
                let sum = 0;
                for (let i = 0; i < pixels.length; ++i) sum += pixels[i];
                return [Number(image.dataset.epoch), sum, canvas.width, canvas.height];""")

        first = wait_for(driver, loaded_epoch, "the job's first image")
        assert first[2:] == [96, 96], first
        second = wait_for(driver, lambda d: (lambda s: s if s and s[0] > first[0] else None)(loaded_epoch(d)),
                          "the image of a later epoch")
        assert second[1] != first[1], f"the image did not change from epoch {first[0]} to {second[0]}"
        print(f"image: epoch {first[0]} sum {first[1]}, epoch {second[0]} sum {second[1]}")

        # The plot's points are the convergence log's.
        wait_for(driver, lambda d: len(d.find_elements(By.CSS_SELECTOR, "#plot circle.estimated")) >= 2,
                 "two points on the error plot")
        # Read in one go: the plot is drawn again with every epoch.
        shown = dict(driver.execute_script("""
            return [...document.querySelectorAll('#plot circle.estimated')].map(
                (c) => [Number(c.dataset.epoch), Number(c.dataset.error)]);"""))
        logged = {int(p["epochs"]): p["estimated_rel_mse"] ** 0.5
                  for p in api(f"/api/jobs/{job_id}")["points"] if "estimated_rel_mse" in p}
        for epoch, error in shown.items():
            assert epoch in logged and abs(error - logged[epoch]) <= 1e-9 * logged[epoch], (epoch, error, logged)
        print(f"plot: {len(shown)} points, all in the convergence log")
        exr = driver.find_element(By.ID, "download-exr").get_attribute("href")
        assert exr.endswith(f"/api/jobs/{job_id}/image.exr"), exr
        driver.save_screenshot(f"{out_dir}/job.png")

        # Cancel.
        driver.find_element(By.ID, "cancel").click()
        wait_for(driver, lambda d: d.find_element(By.ID, "job-state").text == "CANCELLED", "the cancelled state")
        assert api(f"/api/jobs/{job_id}")["status"]["state"] == "JOB_STATE_CANCELLED"
        driver.save_screenshot(f"{out_dir}/job-cancelled.png")

        # The workers page.
        driver.find_element(By.ID, "nav-workers").click()
        wait_for(driver, lambda d: d.find_elements(By.CSS_SELECTOR, "#workers tbody tr"), "the worker")
        cells = [c.text for c in driver.find_elements(By.CSS_SELECTOR, "#workers tbody tr td")]
        assert cells[1] == "cpu" and cells[3] == "1", cells
        driver.save_screenshot(f"{out_dir}/workers.png")

        # photonfarm render --web-listen: the same pages for a render on one machine, with no
        # login (plain HTTP on loopback); cancelling from the page ends the render, which
        # writes its image.
        driver.delete_all_cookies()  # the farm's Secure cookie has the same host
        render = start([photonfarm, "render", f"{source_dir}/scenes/cornell-box.gltf", "--width", "64",
                        "--height", "64", "--threads", "1", "--until-cancelled", "--out", f"{work}/embedded.exr",
                        "--web-listen", "127.0.0.1:0"])
        processes.append(render)
        driver.get(read_until(render, r"watch the render at (http://127\.0\.0\.1:\d+/)").group(1))
        wait_for(driver, lambda d: d.find_elements(By.CSS_SELECTOR, "#jobs tbody tr a"), "the render's job")
        cells = [c.text for c in driver.find_elements(By.CSS_SELECTOR, "#jobs tbody tr td")]
        assert cells[2] == "RUNNING" and cells[11] == "this process", cells
        driver.find_element(By.CSS_SELECTOR, "#jobs tbody tr a").click()
        wait_for(driver, loaded_epoch, "the render's image")
        driver.save_screenshot(f"{out_dir}/render.png")
        driver.find_element(By.ID, "cancel").click()
        assert render.wait(timeout=TIMEOUT) == 0, "".join(l for l in render.lines if l)
        assert os.path.getsize(f"{work}/embedded.exr") > 0
        print(f"screenshots in {out_dir}")
        return 0
    finally:
        if driver is not None:
            driver.quit()
        for process in reversed(processes):
            process.terminate()
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
