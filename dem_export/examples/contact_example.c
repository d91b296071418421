/* Minimal use of the dtwire contact-law C ABI: one macro3d bond with the thesis single-wire
 * calibration, pulled until it breaks. Build: see dem_export/CMakeLists.txt (target
 * contact_example), or by hand:
 *   cc contact_example.c -I<dtwire>/dem_export/include -L<build>/dem_export -ldtwire_contact
 */
#include <stdio.h>

#include "dtwire_contact.h"

int main(void) {
  const char* names[] = {"D_m", "EA_N", "EI_Nm2_per_deg_convention", "N0_N", "Nult_N", "Nc_N",
                         "m_f", "beta_f", "k_F", "k_M", "m_g", "alpha_g", "beta_g",
                         "W1_J", "W2_J", "alpha_d"};
  const double values[] = {0.0027, 1.6e7, 0.122, 2750, 3200, 1650, 0.0285, 0.195, 2.39e4, 1.12e3,
                           4.78, 0.5, 0.0358, 9.21, 140.01, 2.7};
  const size_t count = sizeof(values) / sizeof(values[0]);

  dtwire_bond* bond = dtwire_bond_create("macro3d", names, values, count);
  if (bond == NULL) {
    fprintf(stderr, "cannot create the bond: %s\n", dtwire_contact_last_error());
    return 1;
  }

  const double step[6] = {2.0e-5, 0.0, 0.0, 0.0, 0.0, 0.0}; /* 0.02 mm of elongation */
  double forces[6];
  dtwire_energy energy;
  int i;
  printf("elongation_mm,axial_force_N,external_work_J,plastic_work_J,damage_work_J\n");
  for (i = 1; i <= 5000 && dtwire_bond_broken(bond) == 0; ++i) {
    if (dtwire_bond_update(bond, step) != 0 || dtwire_bond_forces(bond, forces) != 0 ||
        dtwire_bond_energy(bond, &energy) != 0) {
      fprintf(stderr, "update failed: %s\n", dtwire_contact_last_error());
      dtwire_bond_destroy(bond);
      return 1;
    }
    if (i % 250 == 0)
      printf("%.3f,%.3f,%.6f,%.6f,%.6f\n", i * step[0] * 1e3, forces[0], energy.external,
             energy.plastic, energy.damage);
  }
  printf("broken after %.3f mm, failure mode %d (1 = necking)\n", (i - 1) * step[0] * 1e3,
         dtwire_bond_failure_mode(bond));
  dtwire_bond_destroy(bond);

  /* Errors come back as NULL / -1 with a message, never as an exception. */
  if (dtwire_bond_create("no_such_law", NULL, NULL, 0) == NULL)
    printf("expected error: %s\n", dtwire_contact_last_error());
  return 0;
}
