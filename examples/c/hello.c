/* k* and d* of the thesis's block (mu = 0.3, F_N = 2 N, k_T0 = 1282.7 N/mm)
 * at the slip amplitude 4.401e-4 mm and omega = 1.3 rad/s. */
#include <stdio.h>
#include <jointlin.h>

int main(void) {
    jointlin_contact c = {JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_THESIS, 0.3, 2.0, 1282.7};
    jointlin_linearization l;
    int32_t status = jointlin_linearize(&c, 4.401e-4, 1.3, NULL, &l);
    if (status != JOINTLIN_OK) {
        fprintf(stderr, "jointlin: %s\n", jointlin_status_message(status));
        return 1;
    }
    printf("k* = %.6g N/mm, d* = %.6g N s/mm\n", l.k_star, l.d_star);
    return 0;
}
