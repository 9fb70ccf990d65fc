#pragma once
// Numbers for the report's JSON with only the digits a plot can show: a 60 s log or a 600-sample
// profile with 17 significant digits per value would make the report several times larger.
namespace arcplan::report::detail {

// The double nearest to `value` written with `digits` significant decimal digits, so that JSON
// prints it short ("0.12346", not "0.12345999999999999").
double withSignificantDigits(double value, int digits);

}  // namespace arcplan::report::detail
