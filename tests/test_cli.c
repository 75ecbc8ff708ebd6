#include "rf_test.h"
static void t_dummy(void) { RF_CHECK(1); }
const RfTest rf_tests_cli[] = {{"cli_dummy", t_dummy}, RF_TEST_END};
