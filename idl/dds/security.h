// SecurityFiles: the credentials of one DDS Security participant (OMG DDS Security 1.1 with
// Cyclone's builtin authentication, access-control and cryptography plugins).
//
// They go into the participant's QoS as the standard `dds.sec.*` properties, so every
// participant of a process (and of a test) can have its own identity. The plugin libraries are
// named by full path: Debian installs them in a private directory (libddsc0debian/) that
// Cyclone's default lookup (dlopen("libdds_security_auth.so")) does not search; CMake finds
// that directory at build time (GEARPATH_DDS_SECURITY_PLUGIN_DIR), and an empty directory falls
// back to Cyclone's default names. tools/make-security-fixtures.sh makes a test set of these
// files; docs/deployment.md says what each is and what this Cyclone version can promise.
#pragma once

#include <dds/dds.h>

#include <memory>
#include <string>

#include "core/common/result.h"

namespace gearpath::dds {

struct SecurityFiles {
  std::string identity_ca;           // PEM: the CA that signed every participant's certificate
  std::string identity_certificate;  // PEM: this participant's certificate
  std::string identity_private_key;  // PEM: its private key (unencrypted)
  std::string permissions_ca;        // PEM: the CA that signed governance and permissions
  std::string governance;            // S/MIME-signed governance document (.p7s)
  std::string permissions;           // S/MIME-signed permissions of this participant (.p7s)

  // Security is on when any file is named; then all six must be (CheckSecurityFiles).
  bool enabled() const noexcept;
  bool operator==(const SecurityFiles&) const = default;
};

// Every file named and readable; errors name the field (`identity_ca: cannot read /x`).
Status CheckSecurityFiles(const SecurityFiles& files);

// The directory the plugin libraries are loaded from ("" = Cyclone's default library names).
const char* SecurityPluginDirectory() noexcept;

struct QosDeleter {
  void operator()(dds_qos_t* qos) const noexcept { dds_delete_qos(qos); }
};
using QosPtr = std::unique_ptr<dds_qos_t, QosDeleter>;

// A participant QoS carrying the `dds.sec.*` properties for `files` (null if !files.enabled()).
QosPtr SecurityQos(const SecurityFiles& files);

}  // namespace gearpath::dds
