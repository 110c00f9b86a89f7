#!/usr/bin/env bash
# deploy/ validated offline, with no engine and no cluster: the compose file by docker-compose
# itself, the Kubernetes manifests by their structure (what references what: selectors and
# labels, the Secret and the claim the pods mount, the images kustomize renames, the HPA's
# target, probes and resource requests), and by `kubectl kustomize` where kubectl exists.
# Usage: validate_deploy.sh SOURCE_DIR
set -euo pipefail
source_dir=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$source_dir/tests/support/prerequisite.sh"
command -v docker-compose >/dev/null || skip_for_want_of "docker-compose is not installed (deploy/install-deps.sh installs it)"
docker-compose -f "$source_dir/deploy/compose.yaml" config -q
echo "ok   compose.yaml"
python3 - "$source_dir/deploy/k8s" <<'PY'
import os, sys, yaml
k8s = sys.argv[1]
kustomization = yaml.safe_load(open(os.path.join(k8s, "kustomization.yaml")))
docs = []
for name in kustomization["resources"]:
    docs += [(name, d) for d in yaml.safe_load_all(open(os.path.join(k8s, name))) if d]
failures = []
def check(ok, what):
    if not ok: failures.append(what)
by_kind = {}
for name, d in docs:
    for field in ("apiVersion", "kind", "metadata"):
        check(field in d, f"{name}: a document without {field}")
    by_kind.setdefault(d["kind"], {})[d["metadata"]["name"]] = d
secrets = {g["name"] for g in kustomization.get("secretGenerator", [])}
images = {i["name"] for i in kustomization.get("images", [])}
claims = set(by_kind.get("PersistentVolumeClaim", {}))
for name, deployment in by_kind.get("Deployment", {}).items():
    spec = deployment["spec"]
    template = spec["template"]
    labels = template["metadata"]["labels"]
    check(all(labels.get(k) == v for k, v in spec["selector"]["matchLabels"].items()), f"{name}: selector misses the pod labels")
    pod = template["spec"]
    check(pod.get("securityContext", {}).get("runAsNonRoot") is True, f"{name}: not non-root")
    check("terminationGracePeriodSeconds" in pod, f"{name}: no grace period")
    for volume in pod.get("volumes", []):
        if "secret" in volume: check(volume["secret"]["secretName"] in secrets, f"{name}: secret {volume['secret']['secretName']} is not generated")
        if "persistentVolumeClaim" in volume: check(volume["persistentVolumeClaim"]["claimName"] in claims, f"{name}: no claim {volume['persistentVolumeClaim']['claimName']}")
    for container in pod["containers"]:
        check(container["image"] in images, f"{name}: image {container['image']} is not in kustomization images")
        check("requests" in container.get("resources", {}), f"{name}: no resource requests")
        check("livenessProbe" in container, f"{name}: no liveness probe")
        mounted = {m["name"] for m in container.get("volumeMounts", [])}
        check(mounted <= {v["name"] for v in pod.get("volumes", [])}, f"{name}: mounts a volume it does not have")
coordinator = by_kind["Deployment"]["photonfarm-coordinator"]["spec"]["template"]
check("readinessProbe" in coordinator["spec"]["containers"][0], "the coordinator has no readiness probe")
check("health" in coordinator["spec"]["containers"][0]["readinessProbe"]["exec"]["command"], "the readiness probe does not use the gRPC health service")
service = by_kind["Service"]["photonfarm-coordinator"]
check(all(coordinator["metadata"]["labels"].get(k) == v for k, v in service["spec"]["selector"].items()), "the Service selects no coordinator")
workers = by_kind["Deployment"]["photonfarm-worker"]["spec"]["template"]["spec"]["containers"][0]
address = {e["name"]: e.get("value") for e in workers["env"]}["PHOTONFARM_COORDINATOR"]
check(address.split(":")[0] == service["metadata"]["name"], "the workers do not address the coordinator's Service")
hpa = by_kind["HorizontalPodAutoscaler"]["photonfarm-worker"]
check(hpa["spec"]["scaleTargetRef"]["name"] in by_kind["Deployment"], "the HPA scales no Deployment")
check(hpa["spec"]["metrics"][0]["external"]["metric"]["name"] == "photonfarm_batches_pending", "the HPA does not scale on pending batches")
for failure in failures: print("FAIL", failure)
sys.exit(1 if failures else 0)
PY
echo "ok   k8s manifests (structure)"
if command -v kubectl >/dev/null; then
    cp -r "$source_dir/deploy/k8s" "$work/k8s"
    bash "$source_dir/deploy/make-certs.sh" "$work/k8s/secrets" > /dev/null
    kubectl kustomize "$work/k8s" > "$work/rendered.yaml"
    echo "ok   kubectl kustomize: $(grep -c '^kind:' "$work/rendered.yaml") objects"
else
    echo "note kubectl is not installed: kustomize rendering not checked"
fi
