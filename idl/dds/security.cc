#include "idl/dds/security.h"

#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#ifndef GEARPATH_DDS_SECURITY_PLUGIN_DIR
#define GEARPATH_DDS_SECURITY_PLUGIN_DIR ""
#endif

namespace gearpath::dds {
namespace {

std::vector<std::pair<const char*, const std::string*>> Fields(const SecurityFiles& f) {
  return {{"identity_ca", &f.identity_ca},
          {"identity_certificate", &f.identity_certificate},
          {"identity_private_key", &f.identity_private_key},
          {"permissions_ca", &f.permissions_ca},
          {"governance", &f.governance},
          {"permissions", &f.permissions}};
}

// Cyclone's plugins take "file:" URIs (they also accept inline "data:," PEM, unused here).
std::string FileUri(const std::string& path) {
  return "file:" + std::filesystem::absolute(path).lexically_normal().string();
}

std::string Library(const char* name) {
  const std::string dir = SecurityPluginDirectory();
  if (dir.empty()) return name;  // Cyclone adds lib...so and searches the loader's path
  return dir + "/lib" + name + ".so";
}

}  // namespace

bool SecurityFiles::enabled() const noexcept {
  for (const auto& [name, value] : Fields(*this)) {
    if (!value->empty()) return true;
  }
  return false;
}

Status CheckSecurityFiles(const SecurityFiles& files) {
  std::string errors;
  for (const auto& [name, value] : Fields(files)) {
    std::string why;
    if (value->empty()) {
      why = "missing (DDS Security needs all six files)";
    } else if (std::ifstream in(*value, std::ios::binary); !in || in.peek() == EOF) {
      why = "cannot read " + *value;
    }
    if (!why.empty()) errors += (errors.empty() ? "" : "\n") + std::string(name) + ": " + why;
  }
  if (!errors.empty()) return Error{errors};
  return Status::Ok();
}

const char* SecurityPluginDirectory() noexcept { return GEARPATH_DDS_SECURITY_PLUGIN_DIR; }

QosPtr SecurityQos(const SecurityFiles& files) {
  if (!files.enabled()) return nullptr;
  QosPtr qos(dds_create_qos());
  dds_qset_prop(qos.get(), "dds.sec.auth.identity_ca", FileUri(files.identity_ca).c_str());
  dds_qset_prop(qos.get(), "dds.sec.auth.identity_certificate",
                FileUri(files.identity_certificate).c_str());
  dds_qset_prop(qos.get(), "dds.sec.auth.private_key", FileUri(files.identity_private_key).c_str());
  dds_qset_prop(qos.get(), "dds.sec.access.permissions_ca", FileUri(files.permissions_ca).c_str());
  dds_qset_prop(qos.get(), "dds.sec.access.governance", FileUri(files.governance).c_str());
  dds_qset_prop(qos.get(), "dds.sec.access.permissions", FileUri(files.permissions).c_str());
  dds_qset_prop(qos.get(), "dds.sec.auth.library.path", Library("dds_security_auth").c_str());
  dds_qset_prop(qos.get(), "dds.sec.auth.library.init", "init_authentication");
  dds_qset_prop(qos.get(), "dds.sec.auth.library.finalize", "finalize_authentication");
  dds_qset_prop(qos.get(), "dds.sec.access.library.path", Library("dds_security_ac").c_str());
  dds_qset_prop(qos.get(), "dds.sec.access.library.init", "init_access_control");
  dds_qset_prop(qos.get(), "dds.sec.access.library.finalize", "finalize_access_control");
  dds_qset_prop(qos.get(), "dds.sec.crypto.library.path", Library("dds_security_crypto").c_str());
  dds_qset_prop(qos.get(), "dds.sec.crypto.library.init", "init_crypto");
  dds_qset_prop(qos.get(), "dds.sec.crypto.library.finalize", "finalize_crypto");
  return qos;
}

}  // namespace gearpath::dds
