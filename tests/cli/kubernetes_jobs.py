#!/usr/bin/env python3
"""The Kubernetes manifests of deploy/kubernetes run as the Job controller would run them,
without a cluster (none is reachable here; `kubectl --dry-run=server` needs one): each YAML
must parse as one batch/v1 Job; an Indexed Job's TWINLIGHT_SHARD_COUNT must equal its
completions; each pod's shell command runs once per completion index with JOB_COMPLETION_INDEX
set, /data mapped to a scratch folder holding a small content folder, then the merge Job's.
The merged database must hold exactly a one-process bake's rows, the merged report exactly an
unsharded sweep's figures. The compare Job's image size and samples are reduced for the test
(the only edit made to a command; it fails when the manifest no longer holds them).
Usage: kubernetes_jobs.py TWINLIGHT CONTENT_DIR DEPLOY_DIR WORK_DIR"""
import os
import shutil
import sqlite3
import subprocess
import sys

import yaml

tl, content, deploy, work = (os.path.abspath(a) for a in sys.argv[1:5])
here = os.path.dirname(os.path.abspath(__file__))
shutil.rmtree(work, ignore_errors=True)
data = os.path.join(work, "data")
os.makedirs(os.path.join(data, "content"))
for scene in ("cornell", "grove", "plane"):
    for ext in (".gltf", ".bin"):
        shutil.copy(os.path.join(content, scene + ext), os.path.join(data, "content"))
bindir = os.path.join(work, "bin")
os.makedirs(bindir)
os.symlink(tl, os.path.join(bindir, "twinlight"))  # the image has twinlight on PATH

SMALLER = {"--size 640x360 --spp 256 --frames 8": "--size 24x16 --spp 16 --frames 1 --paths direct,legacy"}


def fail(message):
    print("kubernetes_jobs: " + message)
    sys.exit(1)


def load_job(name):
    with open(os.path.join(deploy, "kubernetes", name)) as f:
        docs = [d for d in yaml.safe_load_all(f) if d is not None]
    if len(docs) != 1 or docs[0].get("apiVersion") != "batch/v1" or docs[0].get("kind") != "Job":
        fail(f"{name}: expected one batch/v1 Job")
    job = docs[0]
    pod = job["spec"]["template"]["spec"]
    if pod.get("restartPolicy") != "Never":
        fail(f"{name}: a Job's pods need restartPolicy Never (or OnFailure)")
    (container,) = pod["containers"]
    if container["command"] != ["/bin/sh", "-c"] or len(container["args"]) != 1:
        fail(f"{name}: expected command /bin/sh -c and one script")
    if not any(m["mountPath"] == "/data" for m in container.get("volumeMounts", [])):
        fail(f"{name}: /data is not mounted")
    env = {e["name"]: e["value"] for e in container.get("env", [])}
    return job, container["args"][0], env


def run_pod(name, script, env, index=None):
    script = script.replace("/data", data)
    for big, small in SMALLER.items():
        script = script.replace(big, small)
    pod_env = dict(os.environ, **env)
    pod_env["PATH"] = bindir + os.pathsep + os.environ["PATH"]
    pod_env["LP_NUM_THREADS"] = os.environ.get("LP_NUM_THREADS", "2")  # this machine's, not the manifest's
    if index is not None:
        pod_env["JOB_COMPLETION_INDEX"] = str(index)
    result = subprocess.run(["/bin/sh", "-c", script], env=pod_env, capture_output=True, text=True)
    if result.returncode != 0:
        print(result.stdout + result.stderr)
        fail(f"{name} pod {index} exited with {result.returncode}")
    return result.stdout


def run_indexed(name):
    job, script, env = load_job(name)
    spec = job["spec"]
    if spec.get("completionMode") != "Indexed":
        fail(f"{name}: not an Indexed Job")
    if env.get("TWINLIGHT_SHARD_COUNT") != str(spec["completions"]):
        fail(f"{name}: TWINLIGHT_SHARD_COUNT {env.get('TWINLIGHT_SHARD_COUNT')} != completions {spec['completions']}")
    if name.startswith("compare") and not any(big in script for big in SMALLER):
        fail(f"{name}: the test's size reduction no longer matches the manifest; update SMALLER")
    for index in range(spec["completions"]):
        run_pod(name, script, env, index)
    return spec["completions"], script, env


def run_merge(name, completions):
    job, script, env = load_job(name)
    if "completionMode" in job["spec"]:
        fail(f"{name}: a merge Job is a single pod")
    if env.get("TWINLIGHT_SHARD_COUNT") != str(completions):
        fail(f"{name}: TWINLIGHT_SHARD_COUNT {env.get('TWINLIGHT_SHARD_COUNT')} != the array's {completions}")
    return run_pod(name, script, env)


def rows(db):
    with sqlite3.connect(db) as c:
        baked = c.execute("SELECT key, r, g, b, coverage, view_coverage, view_variance, baker_version, label "
                          "FROM baked ORDER BY key").fetchall()
        overrides = c.execute("SELECT key, r, g, b, label FROM overrides ORDER BY key").fetchall()
    return baked, overrides


# The bake: 4 shards and the merge, against one process over the same (sorted) scenes.
completions, _, _ = run_indexed("bake-job.yaml")
run_merge("bake-merge-job.yaml", completions)
scenes = sorted(os.path.join(data, "content", f) for f in os.listdir(os.path.join(data, "content")) if f.endswith(".gltf"))
single = os.path.join(work, "single.db")
subprocess.run([tl, "bake", "--db", single, "--scene", *scenes], check=True, capture_output=True)
merged = os.path.join(data, "out", "bake", "albedo.db")
if not os.path.exists(merged):
    fail("the merge Job wrote no albedo.db")
if not rows(single)[0] or rows(merged) != rows(single):
    fail("the merged database differs from a one-process bake")
print(f"bake: {completions} indexed pods merged: {len(rows(merged)[0])} rows identical to one process")

# The sweep: 3 shards and the merge, against the same command unsharded.
completions, script, env = run_indexed("compare-job.yaml")
print(run_merge("compare-merge-job.yaml", completions).strip().splitlines()[-1])
run_pod("unsharded compare", script.replace("--shard auto", ""), env, "unsharded")
check = subprocess.run([sys.executable, os.path.join(here, "compare_figures.py"),
                        os.path.join(data, "out", "sweep", "shards", "compare-unsharded"),
                        os.path.join(data, "out", "sweep", "report")])
if check.returncode != 0:
    fail("the merged report's figures differ from the unsharded run's")
print(f"compare: {completions} indexed pods merged: figures identical to the unsharded run")
