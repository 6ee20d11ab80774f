#!/usr/bin/env bash
# Makes a DDS Security test setup for gearpath with openssl (docs/deployment.md, "DDS Security"):
#
#   ca_cert.pem / ca_key.pem       a test CA, used as Identity CA and Permissions CA
#   governance.xml / .p7s          domain rules: only authenticated participants join, discovery
#                                  and liveliness encrypted, every topic encrypted and access-
#                                  controlled (signed by the CA, S/MIME)
#   <who>_cert.pem / _key.pem      identities: gearpathd (the daemon), acquisition (bridge,
#                                  `gearpath sim --publish`, `gearpath replay`), monitor
#                                  (`gearpath monitor`, any results subscriber), recorder
#                                  (`gearpath record`)
#   <who>_permissions.xml / .p7s   what each may do, signed by the CA:
#                                    gearpathd   subscribes blocks and Status, publishes
#                                                results, Status and MachineHealth
#                                    acquisition publishes blocks only
#                                    monitor     subscribes results, Status and
#                                                MachineHealth only
#                                    recorder    subscribes blocks only
#   <who>.security.json            the six files of one participant, absolute paths: the
#                                  daemon's `dds.security` object, or `--dds-security FILE`
#                                  of the gearpath tools
#
# Usage: tools/make-security-fixtures.sh OUT_DIR [--domains MIN-MAX] [--days N]
#                                        [--org NAME]
# The keys are unencrypted and the CA key sits next to them: a TEST setup. A plant keeps the CA
# key offline and ships each host only its own key, certificate and permissions.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
  exit "${1:-0}"
}

out=""
domains="0-230"  # Cyclone 0.10 refuses ids above 230 in these documents
days=3650
org="gearpath test"
while [ $# -gt 0 ]; do
  case "$1" in
    --domains) domains="$2"; shift 2 ;;
    --days) days="$2"; shift 2 ;;
    --org) org="$2"; shift 2 ;;
    -h|--help) usage 0 ;;
    -*) echo "make-security-fixtures: unknown option $1" >&2; usage 2 ;;
    *) [ -z "$out" ] || usage 2; out="$1"; shift ;;
  esac
done
[ -n "$out" ] || usage 2
if ! command -v openssl >/dev/null 2>&1; then
  echo "make-security-fixtures: openssl is not installed (apt-get install openssl)" >&2
  exit 1
fi
domain_min=${domains%-*}
domain_max=${domains#*-}

mkdir -p "$out"
out=$(cd "$out" && pwd)
umask 077
cd "$out"

# Topic names as in config/gearpathd.json (dds.topics); change them here if the plant does.
t_block="gearpath/AccelBlock"
t_block_v2="gearpath/AccelBlockV2"  # the blocks with their load
t_results=("gearpath/DominantPath" "gearpath/SuspectedGear" "gearpath/EnvelopeIndicators"
           "gearpath/ConditionIndicators" "gearpath/Status" "gearpath/MachineHealth")

# EC P-256 keys: supported by Cyclone's authentication plugin and fast to make.
newkey=(-newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes)

openssl req -x509 "${newkey[@]}" -keyout ca_key.pem -out ca_cert.pem -days "$days" \
  -subj "/C=DE/O=$org/CN=gearpath test CA" 2>/dev/null

identity() {  # name common-name
  openssl req -new "${newkey[@]}" -keyout "$1_key.pem" -out "$1.csr" \
    -subj "/C=DE/O=$org/CN=$2" 2>/dev/null
  openssl x509 -req -in "$1.csr" -CA ca_cert.pem -CAkey ca_key.pem -CAcreateserial \
    -out "$1_cert.pem" -days "$days" 2>/dev/null
  rm -f "$1.csr"
}

sign() {  # file.xml -> file.p7s (S/MIME, as Cyclone's access-control plugin reads it)
  openssl smime -sign -in "$1.xml" -text -out "$1.p7s" -signer ca_cert.pem -inkey ca_key.pem
}

topics_xml() {  # topic...
  printf '            <topics>\n'
  for t in "$@"; do printf '              <topic>%s</topic>\n' "$t"; done
  printf '            </topics>\n'
}

cat >governance.xml <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains>
        <id_range><min>$domain_min</min><max>$domain_max</max></id_range>
      </domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
EOF
sign governance

not_before=$(date -u -d '-1 day' +%Y-%m-%dT%H:%M:%S)
not_after=$(date -u -d "+$days days" +%Y-%m-%dT%H:%M:%S)

permissions() {  # name common-name publish-topics(;-separated) subscribe-topics(;-separated)
  local name=$1 cn=$2 pub sub
  IFS=';' read -r -a pub <<<"$3"
  IFS=';' read -r -a sub <<<"$4"
  {
    cat <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="${name}_grant">
      <subject_name>CN=$cn,O=$org,C=DE</subject_name>
      <validity>
        <not_before>$not_before</not_before>
        <not_after>$not_after</not_after>
      </validity>
      <allow_rule>
        <domains>
          <id_range><min>$domain_min</min><max>$domain_max</max></id_range>
        </domains>
EOF
    if [ ${#pub[@]} -gt 0 ]; then
      printf '        <publish>\n'
      topics_xml "${pub[@]}"
      printf '        </publish>\n'
    fi
    if [ ${#sub[@]} -gt 0 ]; then
      printf '        <subscribe>\n'
      topics_xml "${sub[@]}"
      printf '        </subscribe>\n'
    fi
    cat <<EOF
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
EOF
  } >"${name}_permissions.xml"
  sign "${name}_permissions"
  cat >"$name.security.json" <<EOF
{
  "identity_ca": "$out/ca_cert.pem",
  "identity_certificate": "$out/${name}_cert.pem",
  "identity_private_key": "$out/${name}_key.pem",
  "permissions_ca": "$out/ca_cert.pem",
  "governance": "$out/governance.p7s",
  "permissions": "$out/${name}_permissions.p7s"
}
EOF
}

results=$(IFS=';'; echo "${t_results[*]}")
identity gearpathd gearpathd
identity acquisition "gearpath acquisition"
identity monitor "gearpath monitor"
identity recorder "gearpath recorder"
# gearpathd also reads Status: a hot standby watches its primary's.
permissions gearpathd gearpathd "$results" "$t_block;$t_block_v2;gearpath/Status"
permissions acquisition "gearpath acquisition" "$t_block;$t_block_v2" ""
permissions monitor "gearpath monitor" "" "$results"
permissions recorder "gearpath recorder" "" "$t_block;$t_block_v2"
rm -f ca_cert.srl
echo "make-security-fixtures: wrote CA, governance and identities gearpathd, acquisition," \
  "monitor, recorder to $out"
