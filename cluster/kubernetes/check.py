#!/usr/bin/env python3
"""Checks cluster/kubernetes/render-parts.yaml without a Kubernetes cluster.

The YAML must parse; it must hold the parts' volume claim, an Indexed Job whose completions,
parallelism and PARTS agree with the merge Job's PARTS, both Jobs mounting that claim at the
same path; and every container's shell script must pass `sh -n`. Exits non-zero, naming the
problem, otherwise. Needs PyYAML (Debian: python3-yaml).
"""

import pathlib
import subprocess
import sys

import yaml

MANIFEST = pathlib.Path(__file__).with_name("render-parts.yaml")


def fail(message):
    sys.exit(f"{MANIFEST}: {message}")


def env(container, name):
    values = [e["value"] for e in container.get("env", []) if e["name"] == name]
    if len(values) != 1:
        fail(f"container {container['name']} must set {name} once")
    return values[0]


def only_container(job):
    containers = job["spec"]["template"]["spec"]["containers"]
    if len(containers) != 1:
        fail(f"Job {job['metadata']['name']} must have one container")
    return containers[0]


def parts_mount(job, claim):
    """The path where `job` mounts the volume of the claim `claim`."""
    pod = job["spec"]["template"]["spec"]
    if pod.get("restartPolicy") not in ("Never", "OnFailure"):
        fail(f"Job {job['metadata']['name']}: restartPolicy must be Never or OnFailure")
    volumes = [v["name"] for v in pod["volumes"] if v.get("persistentVolumeClaim", {}).get("claimName") == claim]
    if len(volumes) != 1:
        fail(f"Job {job['metadata']['name']} must mount the claim {claim} once")
    mounts = [m["mountPath"] for m in only_container(job)["volumeMounts"] if m["name"] == volumes[0]]
    if len(mounts) != 1:
        fail(f"Job {job['metadata']['name']} must mount volume {volumes[0]} once")
    return mounts[0]


def check_script(job, must_contain):
    container = only_container(job)
    if container.get("command") != ["/bin/sh", "-c"] or len(container.get("args", [])) != 1:
        fail(f"Job {job['metadata']['name']}: expected command /bin/sh -c and one script")
    script = container["args"][0]
    for word in must_contain:
        if word not in script:
            fail(f"Job {job['metadata']['name']}: the script does not use {word}")
    syntax = subprocess.run(["sh", "-n"], input=script, text=True, capture_output=True, check=False)
    if syntax.returncode != 0:
        fail(f"Job {job['metadata']['name']}: sh -n: {syntax.stderr.strip()}")


def main():
    documents = [d for d in yaml.safe_load_all(MANIFEST.read_text()) if d is not None]
    by_kind = {}
    for d in documents:
        by_kind.setdefault(d["kind"], []).append(d)
    claims, jobs = by_kind.get("PersistentVolumeClaim", []), by_kind.get("Job", [])
    if len(claims) != 1 or len(jobs) != 2 or len(documents) != 3:
        fail("expected one PersistentVolumeClaim and two Jobs")
    claim = claims[0]["metadata"]["name"]
    if "ReadWriteMany" not in claims[0]["spec"]["accessModes"]:
        fail(f"claim {claim} must be ReadWriteMany: pods on several nodes write to it")
    indexed = [j for j in jobs if j["spec"].get("completionMode") == "Indexed"]
    if len(indexed) != 1:
        fail("expected exactly one Job with completionMode: Indexed")
    render = indexed[0]
    merge = next(j for j in jobs if j is not render)
    spec = render["spec"]
    parts = int(env(only_container(render), "PARTS"))
    counts = {"completions": spec["completions"], "parallelism": spec["parallelism"],
              "PARTS of the render Job": parts, "PARTS of the merge Job": int(env(only_container(merge), "PARTS"))}
    if len(set(counts.values())) != 1 or parts < 1:
        fail(f"the number of parts must agree and be at least 1: {counts}")
    if parts_mount(render, claim) != parts_mount(merge, claim):
        fail("the two Jobs must mount the parts at the same path")
    check_script(render, ["JOB_COMPLETION_INDEX", "nullpath render", "--part"])
    check_script(merge, ["nullpath merge"])
    print(f"{MANIFEST.name}: ok ({parts} parts, claim {claim}, Jobs {render['metadata']['name']} "
          f"and {merge['metadata']['name']})")


if __name__ == "__main__":
    main()
