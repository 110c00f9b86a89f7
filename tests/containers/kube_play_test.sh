#!/usr/bin/env bash
# The Kubernetes manifests (deploy/k8s) played with `podman kube play`: the coordinator with its
# checkpoint volume and the worker Deployment, whose replica count must take effect: 2 workers
# register, then 3 after the manifests are played again with replicas: 3 (the coordinator
# restarting on its volume on the way). Two adaptations for podman 4.3, which has no cluster:
# the Secret volume becomes a host folder (4.3's kube play crashes on secret volumes), and the
# workers address the coordinator's pod by name (4.3 accepts a Service but gives it no name).
# Usage: kube_play_test.sh BUILD_DIR SOURCE_DIR. Skips (77) where podman cannot run.
BUILD=$1 SOURCE=$2
source "$SOURCE/tests/containers/podman_env.sh"
command -v python3 >/dev/null || skip "python3 is not installed"

network=pfkube$$
secrets=$W/kube-secrets-$$
manifest=$W/kube-$$.yaml
cleanup() {
    set +e
    [ -f "$manifest" ] && podman kube down "$manifest" > /dev/null 2>&1
    podman volume rm -f photonfarm-checkpoints > /dev/null 2>&1
    podman network rm -f "$network" > /dev/null 2>&1
    rm -rf "$secrets" "$manifest"
}
trap cleanup EXIT

build_images
coordinator_pod=photonfarm-coordinator-pod-0  # podman 4.3 names a Deployment's pods so
bash "$SOURCE/deploy/make-certs.sh" "$secrets" localhost 127.0.0.1 "$coordinator_pod" > /dev/null
chmod -R a+rX "$secrets"
podman network create "$network" > /dev/null

# render REPLICAS EXISTING_VOLUME: the manifests as podman 4.3 can play them.
render() {
    python3 - "$SOURCE/deploy/k8s" "$1" "$secrets" "$PF_TAG" "$coordinator_pod" "$2" > "$manifest" <<'PY'
import sys
k8s, replicas, secrets, tag, pod, existing_volume = sys.argv[1:]
text = open(f"{k8s}/coordinator.yaml").read() + "\n---\n" + open(f"{k8s}/worker.yaml").read()
secret_volume = "          secret:\n            secretName: photonfarm-secrets\n            defaultMode: 0440\n"
assert secret_volume in text
text = text.replace(secret_volume, f"          hostPath:\n            path: {secrets}\n            type: Directory\n")
for name in ("coordinator", "worker"):
    text = text.replace(f"image: photonfarm-{name}\n", f"image: {tag}-{name}:test\n")
text = text.replace("imagePullPolicy: IfNotPresent", "imagePullPolicy: Never")
text = text.replace("value: photonfarm-coordinator:50051", f"value: {pod}:50051")
assert "replicas: 4" in text
text = text.replace("replicas: 4", f"replicas: {replicas}")
if existing_volume == "yes":  # podman 4.3 refuses to create a claim's volume twice; the pods mount it by name
    text = "\n---\n".join(d for d in text.split("\n---\n") if "kind: PersistentVolumeClaim" not in d)
print(text)
PY
}

# registered COUNT: waits until COUNT workers are registered with the coordinator.
registered() {
    local count=0
    for _ in $(seq 120); do
        count=$(podman exec "$coordinator_pod-coordinator" photonfarm workers --server 127.0.0.1:50051 \
            --token-file /etc/photonfarm/client-token 2> /dev/null | tail -n +2 | grep -c . || true)
        [ "$count" -eq "$1" ] && return 0
        sleep 1
    done
    echo "FAIL: $count workers registered, expected $1"
    podman ps -a --format '{{.Names}} {{.Status}}'
    podman logs "$coordinator_pod-coordinator" 2>&1 | tail -5
    exit 1
}

existing=no
for replicas in 2 3; do
    [ "$existing" = yes ] && podman kube down "$manifest" > /dev/null 2>&1
    render "$replicas" "$existing"
    say "podman kube play with replicas: $replicas"
    podman kube play --network "$network" "$manifest" > "$W/kube.log" 2>&1 || { cat "$W/kube.log"; exit 1; }
    existing=yes
    pods=$(podman pod ps --format '{{.Name}}' | grep -c '^photonfarm-worker-pod-' || true)
    [ "$pods" -eq "$replicas" ] || { echo "FAIL: $pods worker pods for replicas: $replicas"; exit 1; }
    registered "$replicas"
    say "$replicas workers registered"
done
podman volume exists photonfarm-checkpoints || { echo "FAIL: no volume for the PersistentVolumeClaim"; exit 1; }
say "PASS: the replica count takes effect"
