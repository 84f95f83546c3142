#!/usr/bin/python3
"""The Kubernetes manifests of deploy/kubernetes/, filled in by its submit.sh --print as a
user's run would be, checked offline against the API's own models (Debian's
python3-kubernetes): every field is one the API knows, with the type it takes, and every
required field is there. Then what the recipe relies on: an Indexed Job of as many
completions as shards, whose pods pass their index to --shard, never restarted in place;
a merge judged once; one shared volume.

    k8s_manifests_test.py SUBMIT_SH PLUGIN
"""
import re
import subprocess
import sys

import yaml
from kubernetes import client

KINDS = {("v1", "PersistentVolumeClaim"): "V1PersistentVolumeClaim",
         ("v1", "Pod"): "V1Pod",
         ("batch/v1", "Job"): "V1Job"}
PRIMITIVES = {"str": str, "int": int, "bool": bool, "float": (int, float), "object": object}


def check(value, kind, path, errors):
    """Every key of `value` is a field of model `kind`, recursively, with the right type."""
    if kind in PRIMITIVES:
        if kind == "int" and isinstance(value, bool) or not isinstance(value, PRIMITIVES[kind]):
            errors.append(f"{path}: {value!r} is not {kind}")
        return
    list_of = re.fullmatch(r"list\[(.+)\]", kind)
    if list_of:
        if not isinstance(value, list):
            return errors.append(f"{path}: must be a list")
        for i, item in enumerate(value):
            check(item, list_of.group(1), f"{path}[{i}]", errors)
        return
    dict_of = re.fullmatch(r"dict\(str, (.+)\)", kind)
    if dict_of:
        if not isinstance(value, dict):
            return errors.append(f"{path}: must be a map")
        for key, item in value.items():
            check(item, dict_of.group(1), f"{path}.{key}", errors)
        return
    model = getattr(client, kind)
    if not isinstance(value, dict):
        return errors.append(f"{path}: must be a {kind} object")
    by_json_name = {json_name: name for name, json_name in model.attribute_map.items()}
    for key, item in value.items():
        if key not in by_json_name:
            errors.append(f"{path}.{key}: not a field of {kind} "
                          f"(known: {', '.join(sorted(by_json_name))})")
            continue
        check(item, model.openapi_types[by_json_name[key]], f"{path}.{key}", errors)


def required_fields(document, kind, path):
    """The API client's own constructors refuse a missing required field."""
    try:
        client.ApiClient()._ApiClient__deserialize(document, kind)
    except ValueError as e:
        return [f"{path}: {e}"]
    return []


def main():
    submit, plugin = sys.argv[1], sys.argv[2]
    env = {"ACETATE_IMAGE": "registry.example.org/acetate:1.1", "ACETATE_RUNNER": "runner@x",
           "ACETATE_REGISTRY": "registry.json", "ACETATE_SHARDS": "8", "ACETATE_AT_ONCE": "3",
           "PATH": "/usr/bin:/bin"}
    rendered = subprocess.run(["bash", submit, "--print", plugin, "5", "1"], env=env,
                              check=True, capture_output=True, text=True).stdout
    documents = [d for d in yaml.safe_load_all(rendered) if d is not None]
    errors = []
    by_kind = {}
    for i, d in enumerate(documents):
        kind = KINDS.get((d.get("apiVersion"), d.get("kind")))
        path = f"document {i} ({d.get('kind')} {d.get('metadata', {}).get('name')})"
        if kind is None:
            errors.append(f"{path}: apiVersion/kind not one the recipe should use")
            continue
        check(d, kind, path, errors)
        errors += required_fields(d, kind, path)
        by_kind.setdefault(d["kind"], []).append(d)

    jobs = {j["metadata"]["name"].split("-")[1]: j for j in by_kind.get("Job", [])}
    shard, merge = jobs.get("validate"), jobs.get("merge")
    if not shard or not merge:
        errors.append("expected a validate Job and a merge Job")
    else:
        spec, pod = shard["spec"], shard["spec"]["template"]["spec"]
        container = pod["containers"][0]
        command = " ".join(container.get("command", []) + container.get("args", []))
        env_of = {e["name"]: e.get("value") for e in container.get("env", [])}
        expect = [
            (spec.get("completionMode") == "Indexed", "the shards are an Indexed Job"),
            (spec.get("completions") == 8, "completions equal ACETATE_SHARDS (8)"),
            (spec.get("parallelism") == 3, "parallelism equals ACETATE_AT_ONCE (3)"),
            (env_of.get("ACETATE_SHARDS") == "8", "the pods are told the number of shards"),
            ('--shard "$JOB_COMPLETION_INDEX/$ACETATE_SHARDS"' in command,
             "each pod runs the shard of its own index"),
            (pod.get("restartPolicy") == "Never", "a shard pod is not restarted in place"),
            (merge["spec"].get("backoffLimit") == 0, "the merge is judged once, not retried"),
            ("--junit" in " ".join(merge["spec"]["template"]["spec"]["containers"][0]["command"]),
             "the merge writes JUnit"),
        ]
        errors += [f"validate/merge Job: expected {what}" for ok, what in expect if not ok]
    claims = {v["persistentVolumeClaim"]["claimName"]
              for kind in ("Job", "Pod") for d in by_kind.get(kind, [])
              for v in (d["spec"].get("template", {}).get("spec") or d["spec"]).get("volumes", [])
              if "persistentVolumeClaim" in v}
    pvc = by_kind.get("PersistentVolumeClaim", [{}])[0]
    if claims != {pvc.get("metadata", {}).get("name")}:
        errors.append(f"every pod mounts the one claim the recipe makes; they mount {claims}")
    if "ReadWriteMany" not in pvc.get("spec", {}).get("accessModes", []):
        errors.append("the claim is ReadWriteMany: shards on several nodes write it at once")

    for e in errors:
        print("FAIL:", e)
    print(f"{len(documents)} manifests, every field known to the API (python3-kubernetes "
          f"{client.__version__ if hasattr(client, '__version__') else ''}): "
          f"{'PASS' if not errors else f'{len(errors)} problems'}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
