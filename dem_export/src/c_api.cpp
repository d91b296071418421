// The C ABI of the contact laws: every entry point catches everything, so no exception crosses
// into C; the message is kept per thread for dtwire_contact_last_error().
#include "dtwire_contact.h"

#include <cmath>
#include <exception>
#include <memory>
#include <string>

#include "dtwire/dem/contact_law.hpp"

struct dtwire_bond {
  std::unique_ptr<dtwire::dem::ContactLaw> law;
};

namespace {

thread_local std::string last_error;

template <class Action>
int guarded(Action&& action) noexcept {
  try {
    return action();
  } catch (const std::exception& error) {
    last_error = error.what();
  } catch (...) {
    last_error = "unknown error";
  }
  return -1;
}

int fail(const char* message) {
  last_error = message;
  return -1;
}

}  // namespace

extern "C" {

dtwire_bond* dtwire_bond_create(const char* law_name, const char* const* names, const double* values,
                                size_t count) {
  dtwire_bond* bond = nullptr;
  guarded([&] {
    if (law_name == nullptr) return fail("dtwire_bond_create: law_name is NULL");
    if (count > 0 && (names == nullptr || values == nullptr))
      return fail("dtwire_bond_create: names or values is NULL");
    dtwire::dem::ParameterMap parameters;
    for (size_t i = 0; i < count; ++i) {
      if (names[i] == nullptr) return fail("dtwire_bond_create: a parameter name is NULL");
      parameters[names[i]] = values[i];
    }
    auto made = std::make_unique<dtwire_bond>();
    made->law = dtwire::dem::make_contact_law(law_name, parameters);
    bond = made.release();
    return 0;
  });
  return bond;
}

dtwire_bond* dtwire_bond_clone(const dtwire_bond* bond) {
  dtwire_bond* copy = nullptr;
  guarded([&] {
    if (bond == nullptr) return fail("dtwire_bond_clone: bond is NULL");
    auto made = std::make_unique<dtwire_bond>();
    made->law = bond->law->clone();
    copy = made.release();
    return 0;
  });
  return copy;
}

void dtwire_bond_destroy(dtwire_bond* bond) { delete bond; }

int dtwire_bond_update(dtwire_bond* bond, const double increments[6]) {
  return guarded([&] {
    if (bond == nullptr || increments == nullptr) return fail("dtwire_bond_update: NULL argument");
    for (int i = 0; i < 6; ++i)
      if (!std::isfinite(increments[i])) return fail("dtwire_bond_update: increment is not finite");
    bond->law->update(Eigen::Map<const dtwire::dem::Vector6>(increments));
    return 0;
  });
}

int dtwire_bond_forces(const dtwire_bond* bond, double forces[6]) {
  return guarded([&] {
    if (bond == nullptr || forces == nullptr) return fail("dtwire_bond_forces: NULL argument");
    const dtwire::dem::Vector6 current = bond->law->forces();
    for (int i = 0; i < 6; ++i) forces[i] = current[i];
    return 0;
  });
}

int dtwire_bond_energy(const dtwire_bond* bond, dtwire_energy* energy) {
  return guarded([&] {
    if (bond == nullptr || energy == nullptr) return fail("dtwire_bond_energy: NULL argument");
    const dtwire::dem::EnergyAccount account = bond->law->energy();
    *energy = dtwire_energy{account.external, account.elastic, account.plastic, account.damage};
    return 0;
  });
}

int dtwire_bond_broken(const dtwire_bond* bond) {
  return guarded([&] {
    if (bond == nullptr) return fail("dtwire_bond_broken: bond is NULL");
    return bond->law->broken() ? 1 : 0;
  });
}

int dtwire_bond_failure_mode(const dtwire_bond* bond) {
  return guarded([&] {
    if (bond == nullptr) return fail("dtwire_bond_failure_mode: bond is NULL");
    switch (bond->law->failure_mode()) {
      case dtwire::dem::FailureMode::None: return int{DTWIRE_FAILURE_NONE};
      case dtwire::dem::FailureMode::Necking: return int{DTWIRE_FAILURE_NECKING};
      case dtwire::dem::FailureMode::Shear: return int{DTWIRE_FAILURE_SHEAR};
      case dtwire::dem::FailureMode::Elongation: return int{DTWIRE_FAILURE_ELONGATION};
    }
    return fail("dtwire_bond_failure_mode: unknown failure mode");
  });
}

const char* dtwire_contact_last_error(void) { return last_error.c_str(); }

}  // extern "C"
