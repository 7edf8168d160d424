# Shared by the campaign test scripts (sourced): named checks counted into one verdict.
passed=0
failed=0
check() {  # name, command...
  local name=$1
  shift
  if "$@"; then passed=$((passed + 1)); echo "PASS $name"; else failed=$((failed + 1)); echo "FAIL $name"; fi
}
