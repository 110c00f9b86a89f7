#!/usr/bin/env bash
# Makes what a photonfarm with TLS and tokens needs, into DIR (created; existing files are kept,
# so running it again adds only what is missing):
#   ca.pem, ca.key                      a certificate authority of your own (10 years)
#   coordinator.pem, coordinator.key    the coordinator's certificate, for the names given
#   worker.pem, worker.key              a certificate for workers, for mutual TLS (--worker-ca ca.pem)
#   client-tokens, worker-tokens        one random token each ("NAME SECRET" lines; add more lines
#                                       for more clients, each with its own name)
#   client-token, worker-token          the same secrets alone, for --token-file on a client or worker
# Usage: deploy/make-certs.sh DIR [NAME...]   NAMEs: the coordinator's DNS names or IP addresses
#        (default: localhost 127.0.0.1 coordinator photonfarm-coordinator).
# For a real cluster, prefer your organisation's CA or cert-manager; see docs/operations.md.
set -euo pipefail

[ $# -ge 1 ] || { echo "usage: $0 DIR [NAME...]" >&2; exit 2; }
dir=$1; shift
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(localhost 127.0.0.1 coordinator photonfarm-coordinator)
command -v openssl >/dev/null || { echo "make-certs: openssl is not installed (apt-get install openssl)" >&2; exit 1; }
mkdir -p "$dir"
umask 077

san=""
for name in "${names[@]}"; do
    if [[ $name =~ ^[0-9.]+$ || $name == *:* ]]; then san+="IP:$name,"; else san+="DNS:$name,"; fi
done
san=${san%,}

if [ ! -f "$dir/ca.pem" ]; then
    openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -days 3650 \
        -subj "/CN=photonfarm CA" -keyout "$dir/ca.key" -out "$dir/ca.pem" 2>/dev/null
fi

# sign NAME SUBJECT EXTENSIONS: a key and a certificate signed by the CA.
sign() {
    local name=$1 subject=$2 extensions=$3
    [ -f "$dir/$name.pem" ] && return 0
    openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -subj "$subject" \
        -keyout "$dir/$name.key" -out "$dir/$name.csr" 2>/dev/null
    openssl x509 -req -in "$dir/$name.csr" -CA "$dir/ca.pem" -CAkey "$dir/ca.key" -CAcreateserial -days 825 \
        -extfile <(printf '%s\n' "$extensions") -out "$dir/$name.pem" 2>/dev/null
    rm -f "$dir/$name.csr"
}
sign coordinator "/CN=photonfarm coordinator" "subjectAltName=$san
extendedKeyUsage=serverAuth"
sign worker "/CN=photonfarm worker" "extendedKeyUsage=clientAuth"

for role in client worker; do
    if [ ! -f "$dir/$role-tokens" ]; then
        secret=$(openssl rand -hex 32)
        printf '# NAME SECRET, one per line: tokens the coordinator accepts from %ss\n%s-1 %s\n' \
            "$role" "$role" "$secret" > "$dir/$role-tokens"
        printf '%s\n' "$secret" > "$dir/$role-token"
    fi
done
chmod 0644 "$dir"/*.pem
echo "make-certs: wrote $dir (coordinator names: ${names[*]})"
