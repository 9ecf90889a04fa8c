#!/usr/bin/env bash
# Test certificates for DDS Security (docs/security.md): a CA, an identity
# certificate per participant, and the governance and permissions documents
# signed by the CA (S/MIME), for `./run certs DIR [MATCHES]`.
#
#   certs.sh DIR [MATCHES]
#
# Writes into DIR:
#   ca.pem ca.key                 the CA: identity CA and permissions CA both
#   NAME.pem NAME.key             an identity each: server1 server2 server3 (servers), watch
#                                 (a watcher), load (the load generator, a player of every
#                                 match), and for every match m in 0..MATCHES-1 the players
#                                 m<m>-a and m<m>-b (default MATCHES 2), meant for slots 0
#                                 and 1 (ball-server --slot-owner m:0=m<m>-a --slot-owner m:1=m<m>-b)
#   governance.xml governance.p7s the domain's rules: nobody unauthenticated, everything encrypted
#   permissions.xml permissions.p7s
#                                 a grant per identity: servers write the server topics and read
#                                 the players' in every match partition; a player writes racket
#                                 samples and controls only in its match's partition match/<m>
#                                 (load: in every match/*); a watcher only reads. The five match
#                                 topics in a match's own partition: servers write them in every
#                                 match/*, a player reads its own match's, load and watch every one
# A real deployment makes its own CA and keeps ca.key off the hosts (docs/security.md).
set -euo pipefail
dir=${1:?usage: certs.sh DIR [MATCHES]}
matches=${2:-2}
mkdir -p "$dir"
cd "$dir"

days=3650
subject() { echo "/C=CH/O=libball/CN=$1"; }
# the subject as Fast DDS compares it (RFC 2253: the last component first)
subject_rfc2253() { echo "CN=$1,O=libball,C=CH"; }

# the CA (ECDSA P-256, as PKI-DH supports)
if [ ! -f ca.pem ]; then
  openssl ecparam -name prime256v1 -genkey -noout -out ca.key
  openssl req -x509 -new -key ca.key -sha256 -days "$days" -subj "$(subject "libball test CA")" -out ca.pem \
    -addext basicConstraints=critical,CA:TRUE -addext keyUsage=critical,keyCertSign,cRLSign,digitalSignature
fi

identities=(server1 server2 server3 watch load)
for ((m = 0; m < matches; m++)); do identities+=("m$m-a" "m$m-b"); done

for name in "${identities[@]}"; do
  [ -f "$name.pem" ] && continue
  openssl ecparam -name prime256v1 -genkey -noout -out "$name.key"
  openssl req -new -key "$name.key" -subj "$(subject "$name")" -out "$name.csr"
  openssl x509 -req -in "$name.csr" -CA ca.pem -CAkey ca.key -CAcreateserial -days "$days" -sha256 \
    -out "$name.pem" 2>/dev/null
  rm -f "$name.csr"
done

server_topics="<topic>ball/ball_state</topic><topic>ball/segments</topic><topic>ball/events</topic><topic>ball/match_info</topic><topic>ball/match_model</topic><topic>ball/server_status</topic>"
player_topics="<topic>ball/racket_samples</topic><topic>ball/match_control</topic>"
# the five topics a match's server writes a second time in the match's own partition (docs/protocol.md)
match_topics="<topic>ball/ball_state</topic><topic>ball/segments</topic><topic>ball/events</topic><topic>ball/match_info</topic><topic>ball/match_model</topic>"
views() { echo "<topics>$match_topics</topics><partitions><partition>$1</partition></partitions>"; }
domains="<domains><id_range><min>0</min><max>232</max></id_range></domains>"
not_before=$(date -u -d '-1 day' +%Y-%m-%dT%H:%M:%S)
not_after=$(date -u -d "+$days days" +%Y-%m-%dT%H:%M:%S)
validity="<validity><not_before>$not_before</not_before><not_after>$not_after</not_after></validity>"

cat > governance.xml <<EOF
<?xml version="1.0" encoding="utf-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      $domains
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>ENCRYPT</rtps_protection_kind>
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

grant() {  # NAME RULES
  echo "    <grant name=\"$1\"><subject_name>$(subject_rfc2253 "$1")</subject_name>$validity$2<default>DENY</default></grant>"
}
{
  echo '<?xml version="1.0" encoding="utf-8"?>'
  echo '<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"'
  echo '     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_permissions.xsd">'
  echo '  <permissions>'
  for name in server1 server2 server3; do
    grant "$name" "<allow_rule>$domains<publish><topics>$server_topics</topics></publish><publish>$(views 'match/*')</publish><subscribe><topics>$server_topics</topics></subscribe><subscribe><topics>$player_topics</topics><partitions><partition>match/*</partition></partitions></subscribe></allow_rule>"
  done
  grant watch "<allow_rule>$domains<subscribe><topics>$server_topics</topics></subscribe><subscribe>$(views 'match/*')</subscribe><subscribe><topics>$player_topics</topics><partitions><partition>match/*</partition></partitions></subscribe></allow_rule>"
  grant load "<allow_rule>$domains<publish><topics>$player_topics</topics><partitions><partition>match/*</partition></partitions></publish><subscribe><topics>$server_topics</topics></subscribe><subscribe>$(views 'match/*')</subscribe></allow_rule>"
  for ((m = 0; m < matches; m++)); do
    for p in a b; do
      grant "m$m-$p" "<allow_rule>$domains<publish><topics>$player_topics</topics><partitions><partition>match/$m</partition></partitions></publish><subscribe><topics>$server_topics</topics></subscribe><subscribe>$(views "match/$m")</subscribe><subscribe><topics><topic>ball/racket_samples</topic></topics><partitions><partition>match/$m</partition></partitions></subscribe></allow_rule>"
    done
  done
  echo '  </permissions>'
  echo '</dds>'
} > permissions.xml

for doc in governance permissions; do
  openssl smime -sign -in "$doc.xml" -text -out "$doc.p7s" -signer ca.pem -inkey ca.key
done
echo "certs.sh: ${#identities[@]} identities, governance and permissions signed, in $dir"
