// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of src/windows: Q_n against Table B.2, lower/upper bounds against Table B.1, certificates,
// precision agreement, thin stripes and thresholds against closed forms, the matrix route, errors.
#include "windows/direct.hpp"
#include "windows/overlays.hpp"
#include "windows/polynomial.hpp"
#include "windows/requests.hpp"
#include "windows/verify.hpp"
#include "windows/windows.hpp"

#include <gtest/gtest.h>

#include "tolerance.hpp"

#include "core/scalar.hpp"
#include "reference_tables.hpp"

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using btob::test::bound;
using btob::test::statistical;
using btob::test::ulps;

namespace {

using namespace btob::windows;

// Table B.2 of the paper, copied verbatim from its LaTeX source (developed, factorised), n = 1..10.
struct TableB2Row {
  int n;
  const char* developed;
  const char* factorised;
};
// clang-format off: the rows are the paper's LaTeX, one formula per line
const TableB2Row kTableB2[] =
    {
        {1, R"(\frac{1}{16}r^4 - \frac{1}{4}r^3 - \frac{5}{8}r^2 - \frac{1}{4}r + \frac{1}{16})",
         R"(\frac{1}{16}(r+1)^2(r^2-6r+1))"},
        {2,
         R"(\frac{5}{256}r^8 - \frac{5}{32}r^7 + \frac{3}{64}r^6 - \frac{3}{32}r^5 + \frac{81}{128}r^4 - \frac{3}{32}r^3 + \frac{3}{64}r^2 - \frac{5}{32}r + \frac{5}{256})",
         R"(\frac{1}{256}(r+1)^2(5r^6-50r^5+107r^4-188r^3+107r^2-50r+5))"},
        {3,
         R"(\frac{21}{4096}r^{12} -\frac{73}{1024}r^{11} +\frac{357}{2048}r^{10} +\frac{59}{1024}r^9 +\frac{283}{4096}r^8 +\frac{7}{512}r^7 -\frac{509}{1024}r^6 +\frac{7}{512}r^5 +\frac{283}{4096}r^4 + \frac{59}{1024}r^3 + \frac{357}{2048}r^2 - \frac{73}{1024}r + \frac{21}{4096})",
         R"(\frac{1}{4096}(r^2-1)^2(21r^8 - 292 r^7 + 756 r^6 - 348 r^5 + 1774 r^4 - 348 r^3 + 756 r^2 - 292 r + 21))"},
        {4,
         R"(\frac{85}{65536}r^{16} - \frac{53}{2048}r^{15} + \frac{1095}{8192}r^{14} - \frac{211}{2048}r^{13} - \frac{1277}{16384}r^{12} - \frac{137}{2048}r^{11} - \frac{303}{8192}r^{10} - \frac{111}{2048}r^9 - \frac{17697}{32768}r^8 - \frac{111}{2048}r^7 - \frac{303}{8192}r^6 - \frac{137}{2048}r^5 - \frac{1277}{16384}r^4 - \frac{211}{2048}r^3 + \frac{1095}{8192}r^2 - \frac{53}{2048}r + \frac{85}{65536})",
         R"(\frac{1}{65536}(r + 1)^2(85 r^{14} - 1866 r^{13} + 12407 r^{12} - 29700 r^{11} + 41885 r^{10} - 58454 r^9 + 72599 r^8 - 90296 r^7 + 72599 r^6 - 58454 r^5 + 41885 r^4 - 29700 r^3 + 12407 r^2 - 1866 r + 85))"},
        {5,
         R"(\frac{341}{1048576}r^{20} - \frac{2215}{262144}r^{19} + \frac{35547}{524288}r^{18} - \frac{42543}{262144}r^{17} - \frac{10319}{1048576}r^{16} + \frac{1325}{65536}r^{15} + \frac{2977}{131072}r^{14} - \frac{159}{65536}r^{13} - \frac{17155}{524288}r^{12} - \frac{12721}{131072}r^{11} - \frac{156383}{262144}r^{10} - \frac{12721}{131072}r^9 - \frac{17155}{524288}r^8 - \frac{159}{65536}r^7 + \frac{2977}{131072}r^6 + \frac{1325}{65536}r^5 - \frac{10319}{1048576}r^4 - \frac{42543}{262144}r^3 + \frac{35547}{524288}r^2 - \frac{2215}{262144}r + \frac{341}{1048576})",
         R"(\frac{1}{1048576} (r + 1)^2(341r^{18} - 9542r^{17} + 89837r^{16} - 340304r^{15} + 580452r^{14} - 799400r^{13} + 1042164r^{12} - 1287472r^{11} + 1498470r^{10} - 1811236r^9 + 1498470r^8 - 1287472r^7 + 1042164r^6 - 799400r^5 + 580452r^4 - 340304r^3 + 89837r^2 - 9542r + 341))"},
        {6,
         R"(\frac{1365}{16777216}r^{24} - \frac{5459}{2097152}r^{23} + \frac{119361}{4194304}r^{22} - \frac{249245}{2097152}r^{21} + \frac{1046837}{8388608}r^{20} + \frac{178783}{2097152}r^{19} + \frac{198397}{4194304}r^{18} + \frac{41649}{2097152}r^{17} + \frac{324955}{16777216}r^{16} + \frac{32985}{1048576}r^{15} + \frac{74977}{2097152}r^{14} - \frac{15849}{1048576}r^{13} - \frac{2145421}{4194304}r^{12} - \frac{15849}{1048576}r^{11} + \frac{74977}{2097152}r^{10} + \frac{32985}{1048576}r^9 + \frac{324955}{16777216}r^8 + \frac{41649}{2097152}r^7 + \frac{198397}{4194304}r^6 + \frac{178783}{2097152}r^5 + \frac{1046837}{8388608}r^4 - \frac{249245}{2097152}r^3 + \frac{119361}{4194304}r^2 - \frac{5459}{2097152}r + \frac{1365}{16777216})", R"(\frac{1}{16777216}(r^2 - 1)^2(1365r^{20} - 43672r^{19} + 480174r^{18} - 2081304r^{17} + 3052657r^{16} - 2688672r^{15} + 6418728r^{14} - 2962848r^{13} + 10109754r^{12} - 2709264r^{11} + 14400596r^{10} - 2709264r^9 + 10109754r^8 - 2962848r^7 + 6418728r^6 - 2688672r^5 + 3052657r^4 - 2081304r^3 + 480174r^2 - 43672r + 1365))"},
        {7,
         R"(\frac{5461}{268435456}r^{28} - \frac{51877}{67108864}r^{27} + \frac{1438737}{134217728}r^{26} - \frac{4339241}{67108864}r^{25} + \frac{40022743}{268435456}r^{24} - \frac{1129031}{33554432}r^{23} - \frac{5192403}{67108864}r^{22} - \frac{2073279}{33554432}r^{21} - \frac{6301571}{268435456}r^{20} - \frac{655231}{67108864}r^{19} - \frac{2823425}{134217728}r^{18} - \frac{1836819}{67108864}r^{17} - \frac{4944041}{268435456}r^{16} - \frac{872357}{16777216}r^{15} - \frac{18088117}{33554432}r^{14} - \frac{872357}{16777216}r^{13} - \frac{4944041}{268435456}r^{12} - \frac{1836819}{67108864}r^{11} - \frac{2823425}{134217728}r^{10} - \frac{655231}{67108864}r^9 - \frac{6301571}{268435456}r^8 - \frac{2073279}{33554432}r^7 - \frac{5192403}{67108864}r^6 - \frac{1129031}{33554432}r^5 + \frac{40022743}{268435456}r^4 - \frac{4339241}{67108864}r^3 + \frac{1438737}{134217728}r^2 - \frac{51877}{67108864}r + \frac{5461}{268435456})",
         R"(\frac{1}{268435456}(r + 1)^2(5461r^{26} - 218430r^{25} + 3308873r^{24} - 23756280r^{23} + 84226430r^{22} - 153728828r^{21} + 202461614r^{20} - 267780632r^{19} + 326798079r^{18} - 388436450r^{17} + 444427971r^{16} - 507766768r^{15} + 566161524r^{14} - 638513992r^{13} + 566161524r^{12} - 507766768r^{11} + 444427971r^{10} - 388436450r^9 + 326798079r^8 - 267780632r^7 + 202461614r^6 - 153728828r^5 + 84226430r^4 - 23756280r^3 + 3308873r^2 - 218430r + 5461))"},
        {8,
         R"(\frac{21845}{4294967296}r^{32} - \frac{60073}{268435456}r^{31} + \frac{1010289}{268435456}r^{30} - \frac{8010651}{268435456}r^{29} + \frac{58278227}{536870912}r^{28} - \frac{34802629}{268435456}r^{27} - \frac{15076669}{268435456}r^{26} + \frac{2386713}{268435456}r^{25} + \frac{18759667}{1073741824}r^{24} - \frac{3118757}{268435456}r^{23} - \frac{3881071}{268435456}r^{22} + \frac{3019329}{268435456}r^{21} + \frac{9472389}{536870912}r^{20} - \frac{1744673}{268435456}r^{19} - \frac{8984773}{268435456}r^{18} - \frac{24778123}{268435456}r^{17} - \frac{1259891681}{2147483648}r^{16} - \frac{24778123}{268435456}r^{15} - \frac{8984773}{268435456}r^{14} - \frac{1744673}{268435456}r^{13} + \frac{9472389}{536870912}r^{12} + \frac{3019329}{268435456}r^{11} - \frac{3881071}{268435456}r^{10} - \frac{3118757}{268435456}r^9 + \frac{18759667}{1073741824}r^8 + \frac{2386713}{268435456}r^7 - \frac{15076669}{268435456}r^6 - \frac{34802629}{268435456}r^5 + \frac{58278227}{536870912}r^4 - \frac{8010651}{268435456}r^3 + \frac{1010289}{268435456}r^2 - \frac{60073}{268435456}r + \frac{21845}{4294967296})", R"(\frac{1}{4294967296}(r + 1)^2(21845r^{30} - 1004858r^{29} + 18152495r^{28} - 163470548r^{27} + 775014417r^{26} - 1943400350r^{25} + 2870559579r^{24} - 3759531400r^{23} + 4723541889r^{22} - 5737452490r^{21} + 6689265955r^{20} - 7592770156r^{19} + 8572053469r^{18} - 9579251550r^{17} + 10442693263r^{16} - 11702584944r^{15} + 10442693263r^{14} - 9579251550r^{13} + 8572053469r^{12} - 7592770156r^{11} + 6689265955r^{10} - 5737452490r^9 + 4723541889r^8 - 3759531400r^7 + 2870559579r^6 - 1943400350r^5 + 775014417r^4 - 163470548r^3 + 18152495r^2 - 1004858r + 21845))"},
        {9,
         R"(\frac{87381}{68719476736}r^{36} - \frac{1092259}{17179869184}r^{35} + \frac{43209447}{34359738368}r^{34} - \frac{212853619}{17179869184}r^{33} + \frac{4269713485}{68719476736}r^{32} - \frac{296590343}{2147483648}r^{31} + \frac{252213133}{4294967296}r^{30} + \frac{188040453}{2147483648}r^{29} + \frac{905801569}{17179869184}r^{28} + \frac{159965871}{4294967296}r^{27} + \frac{416297761}{8589934592}r^{26} + \frac{116931159}{4294967296}r^{25} - \frac{243450859}{17179869184}r^{24} - \frac{30883381}{2147483648}r^{23} + \frac{81855995}{4294967296}r^{22} + \frac{79821671}{2147483648}r^{21} + \frac{1070869059}{34359738368}r^{20} - \frac{208374721}{8589934592}r^{19} - \frac{8911424427}{17179869184}r^{18} - \frac{208374721}{8589934592}r^{17} + \frac{1070869059}{34359738368}r^{16} + \frac{79821671}{2147483648}r^{15} + \frac{81855995}{4294967296}r^{14} - \frac{30883381}{2147483648}r^{13} - \frac{243450859}{17179869184}r^{12} + \frac{116931159}{4294967296}r^{11} + \frac{416297761}{8589934592}r^{10} + \frac{159965871}{4294967296}r^9 + \frac{905801569}{17179869184}r^8 + \frac{188040453}{2147483648}r^7 + \frac{252213133}{4294967296}r^6 - \frac{296590343}{2147483648}r^5 + \frac{4269713485}{68719476736}r^4 - \frac{212853619}{17179869184}r^3 + \frac{43209447}{34359738368}r^2 - \frac{1092259}{17179869184}r + \frac{87381}{68719476736})",
         R"(\frac{1}{68719476736}(r^2 - 1)^2(87381r^{32} - 4369036r^{31} + 86593656r^{30} - 860152548r^{29} + 4442813416r^{28} - 11206827036r^{27} + 12834443304r^{26} - 15536207028r^{25} + 24849279468r^{24} - 17306133084r^{23} + 40194497720r^{22} - 17205160596r^{21} + 54565912536r^{20} - 18092456300r^{19} + 70247023272r^{18} - 16425458532r^{17} + 88069872126r^{16} - 16425458532r^{15} + 70247023272r^{14} - 18092456300r^{13} + 54565912536r^{12} - 17205160596r^{11} + 40194497720r^{10} - 17306133084r^9 + 24849279468r^8 - 15536207028r^7 + 12834443304r^6 - 11206827036r^5 + 4442813416r^4 - 860152548r^3 + 86593656r^2 - 4369036r + 87381))"},
        {10,
         R"(\frac{349525}{1099511627776}r^{40} - \frac{2446673}{137438953472}r^{39} + \frac{111323415}{274877906944}r^{38} - \frac{656403031}{137438953472}r^{37} + \frac{16860878795}{549755813888}r^{36} - \frac{13880529647}{137438953472}r^{35} + \frac{35431771167}{274877906944}r^{34} + \frac{3945563655}{137438953472}r^{33} - \frac{51933796943}{1099511627776}r^{32} - \frac{1902386801}{34359738368}r^{31} - \frac{3442320253}{68719476736}r^{30} - \frac{1723679415}{34359738368}r^{29} - \frac{1719740815}{137438953472}r^{28} + \frac{1000292645}{34359738368}r^{27} + \frac{834339215}{68719476736}r^{26} - \frac{947288877}{34359738368}r^{25} - \frac{18459801603}{549755813888}r^{24} - \frac{1260871583}{68719476736}r^{23} - \frac{1215137471}{137438953472}r^{22} - \frac{3475964857}{68719476736}r^{21} - \frac{148356134671}{274877906944}r^{20} - \frac{3475964857}{68719476736}r^{19} - \frac{1215137471}{137438953472}r^{18} - \frac{1260871583}{68719476736}r^{17} - \frac{18459801603}{549755813888}r^{16} - \frac{947288877}{34359738368}r^{15} + \frac{834339215}{68719476736}r^{14} + \frac{1000292645}{34359738368}r^{13} - \frac{1719740815}{137438953472}r^{12} - \frac{1723679415}{34359738368}r^{11} - \frac{3442320253}{68719476736}r^{10} - \frac{1902386801}{34359738368}r^9 - \frac{51933796943}{1099511627776}r^8 + \frac{3945563655}{137438953472}r^7 + \frac{35431771167}{274877906944}r^6 - \frac{13880529647}{137438953472}r^5 + \frac{16860878795}{549755813888}r^4 - \frac{656403031}{137438953472}r^3 + \frac{111323415}{274877906944}r^2 - \frac{2446673}{137438953472}r + \frac{349525}{1099511627776})",
         R"(\frac{1}{1099511627776}(r + 1)^2(349525r^{38} - 20272434r^{37} + 485489003r^{36} - 6201929820r^{35} + 45640128227r^{34} - 196122563810r^{33} + 488332084061r^{32} - 748977095072r^{31} + 957688309140r^{30} - 1227275900840r^{29} + 1441786368492r^{28} - 1711454577424r^{27} + 1967364859836r^{26} - 2191265777608r^{25} + 2428516122820r^{24} - 2696079712096r^{23} + 2926723698166r^{22} - 3177541629564r^{21} + 3418638461194r^{20} - 3715350730536r^{19} + 3418638461194r^{18} - 3177541629564r^{17} + 2926723698166r^{16} - 2696079712096r^{15} + 2428516122820r^{14} - 2191265777608r^{13} + 1967364859836r^{12} - 1711454577424r^{11} + 1441786368492r^{10} - 1227275900840r^9 + 957688309140r^8 - 748977095072r^7 + 488332084061r^6 - 196122563810r^5 + 45640128227r^4 - 6201929820r^3 + 485489003r^2 - 20272434r + 349525))"},
};
// clang-format on

// Parses a LaTeX polynomial in r: terms [+-] [\frac{a}{b} | a] [r[^k | ^{k}]].  Returns power -> coefficient.
std::map<int, mpq_class> parse_latex_poly(const std::string& text) {
  std::string s;
  for (char ch : text)
    if (!std::isspace(static_cast<unsigned char>(ch))) s += ch;
  std::map<int, mpq_class> out;
  std::size_t i = 0;
  auto number = [&]() {
    std::size_t j = i;
    while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    mpz_class v(s.substr(i, j - i));
    i = j;
    return v;
  };
  while (i < s.size()) {
    int sign = 1;
    if (s[i] == '+') ++i;
    else if (s[i] == '-') sign = -1, ++i;
    mpq_class c = 1;
    if (s.compare(i, 6, "\\frac{") == 0) {
      i += 6;
      mpz_class a = number();
      EXPECT_EQ(s.substr(i, 2), "}{");
      i += 2;
      mpz_class b = number();
      EXPECT_EQ(s[i], '}');
      ++i;
      c = mpq_class(a, b);
      c.canonicalize();
    } else if (std::isdigit(static_cast<unsigned char>(s[i]))) {
      c = mpq_class(number());
    }
    int power = 0;
    if (i < s.size() && s[i] == 'r') {
      ++i;
      power = 1;
      if (i < s.size() && s[i] == '^') {
        ++i;
        const bool brace = s[i] == '{';
        if (brace) ++i;
        power = static_cast<int>(number().get_si());
        if (brace) ++i;
      }
    }
    out[power] += sign * c;
  }
  return out;
}

struct ParsedFactorised {
  mpz_class denominator;
  int plus_one = 0, minus_one = 0;
  std::map<int, mpq_class> cofactor;
};

// Parses "\frac{1}{D}(r+1)^2(poly)" or "\frac{1}{D}(r^2-1)^2(poly)".
ParsedFactorised parse_latex_factorised(const std::string& text) {
  std::string s;
  for (char ch : text)
    if (!std::isspace(static_cast<unsigned char>(ch))) s += ch;
  ParsedFactorised f;
  const std::size_t open = s.find('{', s.find('}') + 1), close = s.find('}', open);
  f.denominator = mpz_class(s.substr(open + 1, close - open - 1));
  std::size_t i = close + 1;
  while (i < s.size()) {
    EXPECT_EQ(s[i], '(');
    const std::size_t end = s.find(')', i);
    const std::string inner = s.substr(i + 1, end - i - 1);
    i = end + 1;
    int k = 1;
    if (i < s.size() && s[i] == '^') k = s[i + 1] - '0', i += 2;
    if (inner == "r+1") f.plus_one += k;
    else if (inner == "r-1") f.minus_one += k;
    else if (inner == "r^2-1") f.plus_one += k, f.minus_one += k;
    else f.cofactor = parse_latex_poly(inner);
  }
  return f;
}

struct TableB1Row {
  int n;
  std::string lower, upper;
};
// All 100 rows of Table B.1; throws when the file is missing, short or malformed (btob::testing::table_b1).
std::vector<TableB1Row> read_table_b1() {
  std::vector<TableB1Row> rows;
  for (const auto& f : btob::testing::table_b1().rows) rows.push_back({std::stoi(f[0]), f[1], f[2]});
  return rows;
}

// Expands a parsed factorised row: (1/D) (r+1)^p (r-1)^m cofactor.
std::map<int, mpq_class> expand(const ParsedFactorised& f) {
  std::map<int, mpq_class> acc = f.cofactor;
  auto times_linear = [](const std::map<int, mpq_class>& a, int root) {  // * (r - root)
    std::map<int, mpq_class> out;
    for (const auto& [k, v] : a) out[k + 1] += v, out[k] -= root * v;
    return out;
  };
  for (int i = 0; i < f.plus_one; ++i) acc = times_linear(acc, -1);
  for (int i = 0; i < f.minus_one; ++i) acc = times_linear(acc, 1);
  for (auto& [k, v] : acc) v /= mpq_class(f.denominator);
  return acc;
}

// Known erratum of Table B.2: for n = 2 the developed form prints +81/128 r^4; the paper's own factorised
// form (r+1)^2(5r^6-50r^5+107r^4-...)/256 expands to -81/128 r^4 (107 - 2*188 + 107 = -162), and so do we.
bool is_erratum_b2(int n, int k) { return n == 2 && k == 4; }

TEST(WindowPolynomial, DevelopedFormEqualsTableB2) {
  for (const auto& row : kTableB2) {
    const RationalPoly q = window_polynomial(row.n);
    const auto expected = parse_latex_poly(row.developed);
    const auto from_factorised = expand(parse_latex_factorised(row.factorised));
    ASSERT_EQ(q.degree(), 4 * row.n) << "n = " << row.n;
    for (int k = 0; k <= q.degree(); ++k) {
      const auto it = expected.find(k);
      const mpq_class e = it == expected.end() ? mpq_class(0) : it->second;
      const auto jt = from_factorised.find(k);
      const mpq_class ef = jt == from_factorised.end() ? mpq_class(0) : jt->second;
      EXPECT_EQ(q.coefficient(k), ef) << "n = " << row.n << ", factorised row expanded, coefficient of r^" << k;
      if (is_erratum_b2(row.n, k)) EXPECT_EQ(q.coefficient(k), -e) << "n = " << row.n << ", erratum r^" << k;
      else EXPECT_EQ(q.coefficient(k), e) << "n = " << row.n << ", coefficient of r^" << k;
    }
    EXPECT_EQ(expected.rbegin()->first, 4 * row.n);
  }
}

TEST(WindowPolynomial, FactorisedFormEqualsTableB2) {
  for (const auto& row : kTableB2) {
    const Factorised f = factorise(window_polynomial(row.n));
    const ParsedFactorised e = parse_latex_factorised(row.factorised);
    EXPECT_EQ(f.denominator, e.denominator) << "n = " << row.n;
    EXPECT_EQ(f.plus_one, e.plus_one) << "n = " << row.n;
    EXPECT_EQ(f.minus_one, e.minus_one) << "n = " << row.n;
    ASSERT_EQ(f.cofactor.degree(), e.cofactor.rbegin()->first) << "n = " << row.n;
    for (int k = 0; k <= f.cofactor.degree(); ++k)
      EXPECT_EQ(mpq_class(f.cofactor[static_cast<std::size_t>(k)]),
                e.cofactor.count(k) ? e.cofactor.at(k) : mpq_class(0))
          << "n = " << row.n << ", cofactor coefficient of r^" << k;
  }
}

TEST(WindowPolynomial, PalindromicAndTraceDegree) {
  // r^(4n) Q_n(1/r) = Q_n(r) (Q_n is symmetric by construction) and deg P_n = 2n (Section 4).
  for (int n = 1; n <= 30; ++n) {
    const RationalPoly q = window_polynomial(n);
    EXPECT_EQ(q.numerator.reversed(4 * n), q.numerator) << "n = " << n;
    EXPECT_EQ(trace_polynomial(n).degree(), 2 * n) << "n = " << n;
  }
}

TEST(WindowPolynomial, TraceMatchesFloatingMatrixPower) {
  // P_n(r) from the exact polynomial vs tr(J (BA)^n) in double at r = 0.3 (an independent evaluation).
  const double r = 0.3, a = (1 + r) / 2;
  const double A[9] = {-r, 0, 0, a, 1, 0, 0, 0, 1}, B[9] = {1, a, 0, 0, -r, 0, 0, a, 1};
  double BA[9], M[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) BA[3 * i + j] = B[3 * i] * A[j] + B[3 * i + 1] * A[3 + j] + B[3 * i + 2] * A[6 + j];
  for (int n = 1; n <= 12; ++n) {
    double N[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) N[3 * i + j] = BA[3 * i] * M[j] + BA[3 * i + 1] * M[3 + j] + BA[3 * i + 2] * M[6 + j];
    std::copy(N, N + 9, M);
    const RationalPoly p = trace_polynomial(n);
    mpq_class v = 0, x(3, 10), xp = 1;
    for (int k = 0; k <= p.degree(); ++k, xp *= x) v += p.coefficient(k) * xp;
    EXPECT_CLOSE(v.get_d(), M[6] + M[4] + M[2], ulps(225, "a dozen double products of entries below 2").of(2))
        << "n = " << n;
  }
}

TEST(WindowBounds, LowerBoundsEqualTableB1) {
  for (const auto& row : read_table_b1()) {
    EXPECT_EQ(fixed(window_lower_bound(row.n, 12), 12), row.lower) << "n = " << row.n;
  }
}

// Known erratum of Table B.1: r_crit,2(52) = 0.0718724765988266... (eq. 4.6; also mpmath at 40 digits),
// which rounds to ...599 and truncates to ...598; the paper prints ...597.
bool is_erratum_b1_upper(int n) { return n == 52; }

TEST(WindowBounds, UpperBoundsEqualTableB1) {
  for (const auto& row : read_table_b1()) {
    if (row.n == 1) {
      EXPECT_TRUE(row.upper.empty());
      continue;
    }
    const std::string ours = fixed(r_crit2(row.n, 20), 12);
    if (is_erratum_b1_upper(row.n)) {
      EXPECT_NE(ours, row.upper);
      EXPECT_NE(fixed(r_crit2(row.n, 20), 20).substr(0, 14), row.upper);  // not a truncation either
      EXPECT_EQ(ours.substr(0, 13), row.upper.substr(0, 13));             // first 11 decimals agree
    } else {
      EXPECT_EQ(ours, row.upper) << "n = " << row.n;
    }
  }
}

TEST(WindowBounds, ClosedFormsOfSmallN) {
  // Q_1 = (r+1)^2 (r^2 - 6r + 1)/16: lower bound 3 - 2 sqrt 2; r_crit,2(2) = 3 - 2 sqrt 2 and
  // r_crit,2(3) = (sqrt 3 - sqrt 2)^2 = 5 - 2 sqrt 6 (the thresholds quoted in Section 4).
  const auto th = thresholds(60);
  mpfr_float::default_precision(70);
  const mpfr_float tol("1e-55");  // 60 requested digits, values below 1
  EXPECT_LT(abs(window_lower_bound(1, 60) - th[1].value), tol);
  EXPECT_LT(abs(r_crit2(2, 60) - th[1].value), tol);
  EXPECT_LT(abs(r_crit2(3, 60) - th[2].value), tol);
  // The README of reference/ quotes 16 truncated decimals.
  EXPECT_EQ(fixed(th[0].value, 20).substr(0, 18), "0.0717967697244908");
  EXPECT_EQ(fixed(th[3].value, 20).substr(0, 18), "0.5874010519681994");
}

TEST(WindowBounds, BoundsInsideThreeParticleThresholdAndUpperBound) {
  // 7 - 4 sqrt 3 < lower(n) < r_crit,2(n), and lower(n) decreases with n (Table B.1).
  mpfr_float::default_precision(40);
  const mpfr_float c = thresholds(30)[0].value;
  mpfr_float prev = 1;
  for (int n = 2; n <= 60; ++n) {
    const mpfr_float lo = window_lower_bound(n, 20);
    EXPECT_GT(lo, c) << n;
    EXPECT_LT(lo, r_crit2(n, 20)) << n;
    EXPECT_LT(lo, prev) << n;
    prev = lo;
  }
}

TEST(WindowBounds, TwoPrecisionsAgreeSubset) {
  // 256 vs 512 decimals agree to >= 100 digits (subset here; all n <= 150 in test_long_windows).
  for (int n : {1, 2, 7, 33, 90, 150}) {
    const mpfr_float a = window_lower_bound(n, 256), b = window_lower_bound(n, 512);
    mpfr_float::default_precision(600);
    EXPECT_LT(abs(a - b), mpfr_float("1e-250")) << "n = " << n;  // both correct to >= 256 decimals
  }
}

TEST(WindowCertificates, ValidForOneToForty) {
  // Exact certificates for n = 1..40 (0.06 s in Release; n = 41..150 in test_long_windows).
  for (int n = 1; n <= 40; ++n) {
    const Certificate c = certify_lower_bound(n, 12);
    EXPECT_TRUE(c.valid()) << "n = " << n << " a = " << c.a.get_str() << " signs " << c.sign_a << "," << c.sign_b
                           << " roots(0,a] = " << c.roots_0_a << " roots(a,b) = " << c.roots_a_b;
  }
}

TEST(WindowCertificates, SturmCountsKnownPolynomials) {
  // (x-1)(x-2)(x-3) = x^3 - 6x^2 + 11x - 6: 3 roots in (0, 4], 1 in (1.5, 2.5], none in (3.5, inf).
  const IntPoly p({mpz_class(-6), mpz_class(11), mpz_class(-6), mpz_class(1)});
  const auto seq = sturm_sequence(p);
  EXPECT_EQ(sturm_count(seq, mpq_class(0), mpq_class(4)), 3);
  EXPECT_EQ(sturm_count(seq, mpq_class(3, 2), mpq_class(5, 2)), 1);
  EXPECT_EQ(sturm_count_to_infinity(seq, mpq_class(7, 2)), 0);
  // (x^2 - 2)^2 (x + 5): distinct roots -5, -sqrt2, sqrt2; negative leading coefficient variant too.
  const IntPoly q = IntPoly({mpz_class(-2), mpz_class(0), mpz_class(1)}) *
                    IntPoly({mpz_class(-2), mpz_class(0), mpz_class(1)}) * IntPoly::x_plus(5);
  EXPECT_EQ(sturm_count(sturm_sequence(q), mpq_class(-10), mpq_class(10)), 3);
  EXPECT_EQ(sturm_count(sturm_sequence(mpz_class(-3) * q), mpq_class(-1), mpq_class(10)), 1);  // only sqrt 2
  EXPECT_EQ(sturm_count_to_infinity(sturm_sequence(q), mpq_class(-6)), 3);
  // Palindromic reduction: x^2 + 3x + 1 = x (s + 3).
  EXPECT_EQ(palindromic_reduce(IntPoly({mpz_class(1), mpz_class(3), mpz_class(1)})),
            IntPoly({mpz_class(3), mpz_class(1)}));
}

// Descartes (VCA bisection) against Sturm on the same polynomials and intervals: products of known linear
// factors (roots inside, at the ends, just outside, close pairs), a squared factor, and the reduced Q_n.
IntPoly from_roots(const std::vector<mpq_class>& roots) {
  IntPoly p = IntPoly::constant(1);
  for (const mpq_class& r : roots) p = p * IntPoly({mpz_class(-r.get_num()), mpz_class(r.get_den())});  // den x - num
  return p;
}

TEST(WindowCertificates, DescartesAgreesWithSturm) {
  const std::vector<mpq_class> roots = {mpq_class(1, 3), mpq_class(1, 2),  mpq_class(50001, 100000),
                                        mpq_class(2),    mpq_class(-7, 5), mpq_class(355, 113),
                                        mpq_class(3)};
  const IntPoly p = from_roots(roots) * IntPoly({mpz_class(1), mpz_class(0), mpz_class(1)});  // and x^2 + 1
  const auto seq = sturm_sequence(p);
  // Brackets with dyadic/decimal ends between the roots (never a root), from very short to all of them.
  const std::vector<mpq_class> ends = {
      mpq_class(-2), mpq_class(0),      mpq_class(1, 4), mpq_class(4, 10), mpq_class(500005, 1000000),
      mpq_class(1),  mpq_class(31, 10), mpq_class(1000)};
  int compared = 0;
  for (std::size_t i = 0; i < ends.size(); ++i) {
    for (std::size_t j = i + 1; j < ends.size(); ++j, ++compared)
      EXPECT_EQ(descartes_count(p, ends[i], ends[j]), sturm_count(seq, ends[i], ends[j]))
          << ends[i].get_str() << " " << ends[j].get_str();
    EXPECT_EQ(descartes_count_to_infinity(p, ends[i]), sturm_count_to_infinity(seq, ends[i])) << ends[i].get_str();
    std::vector<IntPoly> cache;
    EXPECT_EQ(root_count_to_infinity(p, ends[i], &cache), sturm_count_to_infinity(seq, ends[i]));
  }
  EXPECT_EQ(compared, 28);
  // Roots at the ends: Descartes counts the open interval; Sturm (which refuses root ends) on a slightly
  // smaller interval that holds the same roots (the roots are >= 1e-5 apart).
  const mpq_class eps(1, 10000000);
  for (std::size_t i = 0; i < roots.size(); ++i)
    for (std::size_t j = 0; j < roots.size(); ++j) {
      if (!(roots[i] < roots[j])) continue;
      EXPECT_EQ(descartes_count(p, roots[i], roots[j]), sturm_count(seq, roots[i] + eps, roots[j] - eps))
          << roots[i].get_str() << " " << roots[j].get_str();
    }
  // Exact counts by construction: 6 positive roots, 2 of them in (0.49, 0.51) (one at the first midpoint),
  // one in (3, inf) (355/113), none in (3, 355/113) nor (355/113, inf).
  EXPECT_EQ(descartes_count_to_infinity(p, mpq_class(0)), 6);
  EXPECT_EQ(descartes_count(p, mpq_class(49, 100), mpq_class(51, 100)), 2);
  EXPECT_EQ(descartes_count_to_infinity(p, mpq_class(3)), 1);
  EXPECT_EQ(descartes_count(p, mpq_class(3), mpq_class(355, 113)), 0);
  EXPECT_EQ(descartes_count_to_infinity(p, mpq_class(355, 113)), 0);
  // A double root: Descartes cannot separate it (-1), root_count falls back to Sturm (one distinct root).
  const IntPoly sq = from_roots({mpq_class(1, 3), mpq_class(1, 3), mpq_class(2)});
  EXPECT_EQ(descartes_count(sq, mpq_class(0), mpq_class(1)), -1);
  std::vector<IntPoly> cache;
  EXPECT_EQ(root_count(sq, mpq_class(0), mpq_class(1), &cache), 1);
  EXPECT_FALSE(cache.empty());
  EXPECT_EQ(root_count(sq, mpq_class(0), mpq_class(5), &cache), 2);
  // Roots at every bisection point: counted once each.
  const IntPoly mid = from_roots({mpq_class(1, 2), mpq_class(1, 4), mpq_class(3, 4), mpq_class(1, 8)});
  EXPECT_EQ(descartes_count(mid, mpq_class(0), mpq_class(1)), 4);
  EXPECT_EQ(descartes_count(mid, mpq_class(1, 8), mpq_class(3, 4)), 2);
}

TEST(WindowCertificates, DescartesAgreesWithSturmOnReducedQn) {
  // The certificate's polynomials: the reduced cofactor of Q_n, on (s_b, s_a) around its largest root and
  // on (s_a, inf), and on brackets around the other sign changes of Q_n in (0, 1).
  for (int n : {2, 5, 13, 30}) {
    const RationalPoly q = window_polynomial(n);
    const IntPoly red = palindromic_reduce(factorise(q).cofactor);
    const auto seq = sturm_sequence(red);
    for (int k = 3; k <= 40; ++k) {  // s in (k/2 + 1/7, k/2 + 9/14), skipped if an end is a root
      const mpq_class s0(7 * k + 2, 14), s1(7 * k + 9, 14);
      if (red.sign_at(s0) == 0 || red.sign_at(s1) == 0) continue;
      EXPECT_EQ(descartes_count(red, s0, s1), sturm_count(seq, s0, s1)) << "n = " << n << " k = " << k;
      EXPECT_EQ(descartes_count_to_infinity(red, s0), sturm_count_to_infinity(seq, s0)) << "n = " << n << " k = " << k;
    }
    const Certificate c = certify_lower_bound(n, 12);
    const mpq_class sa = c.a + 1 / c.a, sb = c.b + 1 / c.b;
    EXPECT_EQ(descartes_count(red, sb, sa), 1);
    EXPECT_EQ(sturm_count(seq, sb, sa), 1);
    EXPECT_EQ(descartes_count_to_infinity(red, sa), 0);
    EXPECT_EQ(sturm_count_to_infinity(seq, sa), 0);
  }
}

TEST(WindowCertificates, CertificateRejectsWrongInterval) {
  // The certifier itself must reject brackets that do not prove the smallest positive root of Q_5 (0.07964890975):
  const mpq_class a(796489, 10000000), b(796490, 10000000);  // 0.0796489 < root < 0.0796490
  const Certificate good = certify_interval(5, a, b);
  EXPECT_TRUE(good.valid()) << good.sign_a << "," << good.sign_b << " " << good.roots_0_a << " " << good.roots_a_b;
  // the next bracket up: no sign change
  const Certificate above = certify_interval(5, mpq_class(796490, 10000000), mpq_class(796491, 10000000));
  EXPECT_GT(above.sign_a * above.sign_b, 0);
  EXPECT_FALSE(above.valid());
  // A wide bracket that still holds only this root is a proof too.
  EXPECT_TRUE(certify_interval(5, mpq_class(7, 100), mpq_class(8, 100)).valid());
  // Reversed and non-positive brackets.
  EXPECT_FALSE(certify_interval(5, b, a).valid());
  EXPECT_FALSE(certify_interval(5, mpq_class(0), b).valid());
  // A sign change of Q_5 around a larger root: the signs alone would "prove" it, Sturm's count of roots in
  // (0, a] must reject it.  The larger roots are found by scanning Q_5's sign on a grid of 1/1000.
  const RationalPoly q = window_polynomial(5);
  int larger = 0;
  for (int k = 81; k < 1000; ++k) {
    const mpq_class lo(k, 1000), hi(k + 1, 1000);
    if (q.numerator.sign_at(lo) * q.numerator.sign_at(hi) >= 0) continue;
    const Certificate wrong = certify_interval(5, lo, hi);
    EXPECT_NE(wrong.sign_a * wrong.sign_b, 0);
    EXPECT_GE(wrong.roots_0_a, 1) << "bracket (" << k << ", " << k + 1 << ")/1000";
    EXPECT_FALSE(wrong.valid()) << "bracket (" << k << ", " << k + 1 << ")/1000";
    ++larger;
  }
  EXPECT_GE(larger, 1) << "Q_5 has no other sign change in (0.081, 1): the Sturm rejection above was not exercised";
  // The certificate of n = 5 brackets the same root as the one above.
  const Certificate c = certify_lower_bound(5, 12);
  EXPECT_TRUE(c.valid());
  EXPECT_TRUE(c.a > a && c.b < b) << c.a.get_str() << " " << c.b.get_str();
  EXPECT_EQ(c.decimals, 12);
}

TEST(WindowDirect, MatrixRouteAgreesWithPolynomialRoots) {
  // The matrix route (no huge coefficients) in MPFR with 60 digits vs the certified polynomial root.
  for (int n : {1, 2, 5, 20, 75, 150}) {
    const mpfr_float exact = window_lower_bound(n, 40);
    mpfr_float::default_precision(60);
    const mpfr_float m = window_lower_bound_in<mpfr_float>(n, Route::matrix);
    EXPECT_LT(abs(m - exact), mpfr_float("1e-40"))
        << "n = " << n;  // 60 digits minus ~20 lost near the double eigenvalue
  }
  // In double the matrix route is exact to 12 decimals for small n (the precision study measures the limit).
  for (int n = 1; n <= 10; ++n)
    EXPECT_CLOSE(window_lower_bound_in<double>(n, Route::matrix), static_cast<double>(window_lower_bound(n, 20)),
                 ulps(2250, "the matrix route in double, good to 12 decimals for small n"))
        << n;
  // The sign convention: Q_n > 0 at 7 - 4 sqrt 3 and < 0 at r_crit,2(n).
  EXPECT_GT(window_condition<double>(10, 7 - 4 * std::sqrt(3.0)), 0);
  EXPECT_LT(window_condition<double>(10, static_cast<double>(r_crit2(10, 20))), 0);
}

TEST(ThinStripes, RotationAngleIsTwoPiLOverM) {
  // eq. (6.3) inverts cos(beta) = -(1-r)^2/(4r) (Section 6.1): check cos(2 pi l/m) = -(1-r)^2/(4r).
  const auto stripes = thin_stripes(40, 50);
  mpfr_float::default_precision(60);
  const mpfr_float pi = boost::math::constants::pi<mpfr_float>();
  ASSERT_FALSE(stripes.empty());
  for (const auto& s : stripes) {
    const mpfr_float r = s.value;
    EXPECT_LT(abs(cos(2 * pi * s.l / s.m) + (1 - r) * (1 - r) / (4 * r)), mpfr_float("1e-45")) << s.l << "/" << s.m;
    EXPECT_GE(r, thresholds(50)[1].value - mpfr_float("1e-45"));
    EXPECT_LT(r, 1);
  }
  EXPECT_EQ(stripes.front().l * 2, stripes.front().m);  // r(1/2) = 3 - 2 sqrt 2 is the smallest
  // Count: reduced l/m with 1/4 < l/m <= 1/2, m <= 40.
  int count = 0;
  for (int m = 1; m <= 40; ++m)
    for (int l = 1; 2 * l <= m; ++l)
      if (std::gcd(l, m) == 1 && 4 * l > m) ++count;
  EXPECT_EQ(static_cast<int>(stripes.size()), count);
}

TEST(WindowErrors, MessagesNameTheField) {
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no throw");
  };
  EXPECT_EQ(message([] { window_polynomial(0); }),
            "n: got 0, expected an integer in 1..5000 (Q_n costs minutes at n = 5000)");
  EXPECT_EQ(message([] { window_polynomial(5001); }),
            "n: got 5001, expected an integer in 1..5000 (Q_n costs minutes at n = 5000)");
  EXPECT_EQ(message([] { r_crit2(1, 20); }),
            "n: got 1, expected an integer in 2..5000 (Q_n costs minutes at n = 5000)");
  EXPECT_EQ(message([] { window_lower_bound(3, 9); }), "digits: got 9, expected 10..10000");
  EXPECT_EQ(message([] { window_lower_bound(3, 10001); }), "digits: got 10001, expected 10..10000");
  EXPECT_EQ(message([] { thin_stripes(0, 20); }), "m: got 0, expected an integer in 1..100000");
}

TEST(WindowVerify, IteratorSeesPatternInsideAndNotBelowTwoToTwenty) {
  // Section 4: inside (lower, r_crit,2) all 32 orbits of the paper grid end on (1^n 3^n); 5% of the
  // width below the lower bound none does.
  const auto rows = verify_windows(2, 20);
  ASSERT_EQ(rows.size(), 19u * 4u);
  for (const auto& row : rows)
    EXPECT_TRUE(row.pass()) << "n = " << row.n << " " << row.position << " r = " << row.r << ": " << row.on_pattern
                            << " of " << row.orbits << " on pattern";
}

TEST(WindowVerify, PatternDetector) {
  const std::vector<std::uint8_t> good{1, 1, 3, 3, 1, 1, 3, 3, 1, 1}, rotated{3, 1, 1, 3, 3, 1, 1, 3, 3, 1},
      wrong{1, 3, 1, 3, 1, 3, 1, 3, 1, 3}, broken{1, 1, 3, 3, 1, 1, 3, 2, 1, 1};
  EXPECT_TRUE(on_pattern(good.data(), 10, 2));
  EXPECT_TRUE(on_pattern(rotated.data(), 10, 2));
  EXPECT_FALSE(on_pattern(wrong.data(), 10, 2));  // (13)^n is the n = 1 pattern, not n = 2
  EXPECT_TRUE(on_pattern(wrong.data(), 10, 1));
  EXPECT_FALSE(on_pattern(broken.data(), 10, 2));  // one symbol 2 breaks it
  EXPECT_FALSE(on_pattern(good.data(), 7, 2));     // shorter than two periods
}

// ---- the request API (windows/requests.hpp) ----------------------------------------------------------------

// The message of the InvalidField a callable throws ("no throw" otherwise), and its field.
template <class F> std::pair<std::string, std::string> invalid(F&& f) {
  try {
    f();
  } catch (const btob::core::InvalidField& e) {
    return {e.field, e.what()};
  }
  return {"", "no throw"};
}

TEST(WindowRequests, RangesParseAndRefuseWithTheField) {
  EXPECT_EQ(parse_n_range("7").first, 7);
  EXPECT_EQ(parse_n_range("7").last, 7);
  EXPECT_EQ(parse_n_range("1..150").count(), 150);
  EXPECT_EQ(parse_n_range("2..5000", 2).last, 5000);
  EXPECT_EQ(invalid([] { parse_n_range("0"); }).second, "n: got '0', expected A..B or A with 1 <= A <= B <= 5000");
  EXPECT_EQ(invalid([] { parse_n_range("1..3", 2); }).second,
            "n: got '1..3', expected A..B or A with 2 <= A <= B <= 5000");
  for (const char* bad : {"", "..", "1..", "..3", "3..2", "5001", "1..5001", "a", "1..3x", " 1", "+1", "1...3",
                          "99999999999999999999", "-1..3", "1.5"})
    EXPECT_EQ(invalid([&] { parse_n_range(bad, 1, "range"); }).first, "range") << bad;
}

TEST(WindowRequests, ValidationNamesTheField) {
  EXPECT_EQ(invalid([] { BoundsRequest{"1..3", 5}.validate(); }).second, "digits: got 5, expected 10..10000");
  EXPECT_EQ(invalid([] { BoundsRequest{"1..3", 20000}.validate(); }).first, "digits");
  EXPECT_EQ(invalid([] { BoundsRequest{"0"}.validate(); }).first, "n");
  EXPECT_EQ(invalid([] { PolyRequest{"1", "latex"}.validate(); }).first, "form");
  EXPECT_EQ(invalid([] { ThresholdsRequest{9}.validate(); }).first, "digits");
  EXPECT_EQ(invalid([] { StripesRequest{0}.validate(); }).second, "max-m: got 0, expected 1..100000");
  EXPECT_EQ(invalid([] { VerifyRequest{"1..3"}.validate(); }).first, "n");
  EXPECT_EQ(invalid([] { VerifyRequest{"2..3", 50}.validate(); }).first, "iterations");
  EXPECT_EQ(invalid([] { VerifyRequest{"2..3", 1000, -1}.validate(); }).first, "per-n");
  EXPECT_EQ(invalid([] { VerifyRequest{"2..3", 1000, 0, 1000}.validate(); }).first, "tail");
  EXPECT_EQ(invalid([] { VerifyRequest{"2..3", 1000, 0, 10, "float"}.validate(); }).first, "precision");
  EXPECT_EQ(invalid([] {
              BoundPrecisionRequest{"1..3", 9}.validate();
            }).second,
            "mpfr-digits: got 9, expected 10..1000");
  EXPECT_EQ(invalid([] { run(BoundsRequest{"5..4"}); }).first, "n");  // run validates too
}

TEST(WindowRequests, PolyTextIsTheExactPolynomials) {
  const PolyResult both = run(PolyRequest{"1..4", "both"});
  std::string want;
  for (int n = 1; n <= 4; ++n) {
    const RationalPoly q = window_polynomial(n);
    want += "Q_" + std::to_string(n) + " = " + q.developed() + "\n";
    want += "Q_" + std::to_string(n) + " = " + factorise(q).to_string() + "\n";
    EXPECT_EQ(both.degree[static_cast<std::size_t>(n - 1)], static_cast<std::uint32_t>(4 * n));
  }
  EXPECT_EQ(both.text(), want);
  const PolyResult dev = run(PolyRequest{"2", "developed"});
  EXPECT_EQ(dev.text(), "Q_2 = " + window_polynomial(2).developed() + "\n");
}

TEST(WindowRequests, BoundsEqualTableB1AndTheCertificatesHold) {
  const auto table = read_table_b1();
  ASSERT_GE(table.size(), 20u);
  const unsigned ambient = btob::core::mpfr_float::default_precision();
  const BoundsResult res = run(BoundsRequest{"1..20", 12, true});
  EXPECT_EQ(btob::core::mpfr_float::default_precision(), ambient);  // the decimals of a, b printed under a guard
  ASSERT_EQ(res.n.size(), 20u);
  for (std::size_t i = 0; i < 20; ++i) {
    EXPECT_EQ(res.lower_text[i], table[i].lower) << "n = " << res.n[i];
    if (res.n[i] >= 2) EXPECT_EQ(res.upper_text[i], table[i].upper) << "n = " << res.n[i];
    EXPECT_TRUE(res.certificates[i].valid()) << "n = " << res.n[i];
    // The printed a, b are the exact certificate fractions k/10^12, (k+1)/10^12 and bracket the lower bound.
    const mpq_class scaled = res.certificates[i].a * mpq_class(mpz_class("1000000000000"));
    ASSERT_EQ(scaled.get_den(), 1);
    const std::string k = scaled.get_num().get_str();
    EXPECT_EQ(res.a_text[i], "0." + std::string(12 - k.size(), '0') + k);
    EXPECT_LE(std::stod(res.a_text[i]), res.lower_bound[i]);
    EXPECT_GE(std::stod(res.b_text[i]), res.lower_bound[i]);
    // Independent route: bisection on the sign of Q_n from 3x3 matrix powers in long double.
    EXPECT_CLOSE(static_cast<double>(window_lower_bound_in<long double>(static_cast<int>(res.n[i]), Route::matrix)),
                 res.lower_bound[i], ulps(4, "a long double bisection rounded to double"));
  }
  const std::string csv = res.csv();
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "n,lower_bound,upper_bound,a,b,sign_Q_a,sign_Q_b,sturm_roots_0_a,sturm_roots_a_b,certified,lower_status,"
            "upper_status");
  // The certificate proves the lower bound; r_crit,2(n) stays the paper's conjecture (docs/reference/numbers.md).
  EXPECT_NE(
      csv.find("\n2,0.127544097592,0.171572875254,0.127544097591,0.127544097592,1,-1,0,1,yes,certified,conjectured\n"),
      std::string::npos);
  btob::core::Contents c;
  res.describe(c);
  ASSERT_NE(c.find("lower_bound"), nullptr);
  EXPECT_EQ(c.find("lower_bound")->size(), 20u);
  EXPECT_EQ(c.find("certified")->size(), 20u);
}

TEST(WindowRequests, ThresholdsAndStripesAgainstClosedForms) {
  const ThresholdsResult t = run(ThresholdsRequest{30});
  ASSERT_EQ(t.value.size(), 4u);
  // Python's decimal module, 60 digits, rounded to 30 decimals (an independent arbitrary-precision route).
  EXPECT_EQ(t.text[0], "0.071796769724490825890214633977");                         // 7 - 4 sqrt 3
  EXPECT_EQ(t.text[1], "0.171572875253809902396622551581");                         // 3 - 2 sqrt 2
  EXPECT_EQ(t.text[2], "0.101020514433643803605431850588");                         // 5 - 2 sqrt 6
  EXPECT_EQ(t.text[3], "0.587401051968199474751705639272");                         // 2^(2/3) - 1
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(t.value[i], std::stod(t.text[i]));  // both correctly rounded
  // The closed forms in double lose to cancellation: 7 - 4 sqrt 3 errs by up to ulp(4 sqrt 3) ~ 8.9e-16 plus
  // the final rounding, so 2e-15 absolute.
  const auto closed = ulps(9, "cancellation: ulp(4 sqrt 3) = 4 eps, plus the final rounding");
  EXPECT_CLOSE(t.value[0], 7 - 4 * std::sqrt(3.0), closed);
  EXPECT_CLOSE(t.value[1], 3 - 2 * std::sqrt(2.0), closed);
  EXPECT_CLOSE(t.value[2], 5 - 2 * std::sqrt(6.0), closed);
  EXPECT_CLOSE(t.value[3], std::cbrt(4.0) - 1, closed);
  const StripesResult s = run(StripesRequest{40, 20});
  std::size_t count = 0;
  for (int m = 1; m <= 40; ++m)
    for (int l = 1; 2 * l <= m; ++l) count += std::gcd(l, m) == 1 && 4 * l > m;
  ASSERT_EQ(s.r.size(), count);
  for (std::size_t i = 0; i < s.r.size(); ++i) {
    const double xi = std::cos(M_PI - 2 * M_PI * s.l[i] / s.m[i]);
    // eq. (6.3) in double: sqrt(xi + xi^2) loses relative accuracy only near xi = 0 (l/m = 1/4, excluded).
    EXPECT_CLOSE(s.r[i], 1 + 2 * xi - 2 * std::sqrt(xi + xi * xi), ulps(45, "eq. (6.3) in double, away from xi = 0"))
        << s.l[i] << "/" << s.m[i];
    EXPECT_EQ(s.mirror_l[i], s.m[i] - s.l[i]);
    if (i > 0) EXPECT_LT(s.r[i - 1], s.r[i]);
  }
}

TEST(WindowRequests, VerifyIsDeterministicAcrossThreads) {
  VerifyRequest req{"2..6"};
  btob::core::RunControl one, two;
  one.threads = 1;
  two.threads = 2;
  const VerifyResult a = run(req, one), b = run(req, two);
  EXPECT_EQ(a.csv(), b.csv());
  EXPECT_EQ(a.total, 20);
  EXPECT_EQ(a.passed, 20);
  EXPECT_EQ(verify_stem(a.range), "verify_2-6");
  EXPECT_EQ(verify_stem({2, 125}), "verify");
  // The rows are those of verify_windows itself.
  const auto rows = verify_windows(2, 6);
  ASSERT_EQ(rows.size(), a.rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].on_pattern, a.rows[i].on_pattern);
}

TEST(WindowRequests, CancelledRunThrows) {
  btob::core::CancelToken token;
  token.cancel();
  btob::core::RunControl control;
  control.cancel = &token;
  EXPECT_THROW(run(BoundsRequest{"1..3"}, control), btob::core::Cancelled);
  EXPECT_THROW(run(VerifyRequest{"2..3"}, control), btob::core::Cancelled);
}

// MPFR's default precision is process state: the precision study holds its rows' digits with guards, so two runs
// at different precisions in one process give what each gives alone, and the ambient precision is left as it was.
TEST(WindowRequests, PrecisionStudyRunsAtTwoPrecisionsInOneProcess) {
  using btob::core::mpfr_float;
  const unsigned ambient = mpfr_float::default_precision();
  const BoundPrecisionResult a = run(BoundPrecisionRequest{"1..12", 20});
  EXPECT_EQ(mpfr_float::default_precision(), ambient);
  const BoundPrecisionResult b = run(BoundPrecisionRequest{"1..12", 60});
  EXPECT_EQ(mpfr_float::default_precision(), ambient);
  const BoundPrecisionResult a2 = run(BoundPrecisionRequest{"1..12", 20});
  ASSERT_EQ(a.rows.size(), a2.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.rows[i].value, a2.rows[i].value) << a.rows[i].precision << " n = " << a.rows[i].n;
    EXPECT_TRUE(a.rows[i].abs_error == a2.rows[i].abs_error ||
                (std::isnan(a.rows[i].abs_error) && std::isnan(a2.rows[i].abs_error)));
  }
  // Each MPFR row equals the bound computed alone under its own digits (a separate route through the same
  // bisection), whatever ran before.
  for (const auto* res : {&a, &b}) {
    const int digits = res == &a ? 20 : 60;
    for (const auto& row : res->rows) {
      if (row.precision.rfind("mpfr:", 0) != 0) continue;
      btob::core::MpfrDigits guard(digits);
      const mpfr_float alone =
          window_lower_bound_in<mpfr_float>(row.n, row.route == "matrix" ? Route::matrix : Route::polynomial);
      EXPECT_EQ(row.value, static_cast<double>(alone)) << row.precision << " " << row.route << " n = " << row.n;
    }
  }
  // 60 digits resolve every bound to 12 decimals by both routes; the summary says so.
  for (const auto& m : b.summary)
    if (m.precision == "mpfr:60") EXPECT_EQ(m.largest_all, 12) << m.route;
  btob::core::Contents c;
  b.describe(c);
  EXPECT_EQ(c.find("value")->dims, (std::vector<std::size_t>{10, 12}));
}

// The first use computes the bounds; two callers at once (the explorer's server threads) must take turns, since
// MPFR's precision is one per process (core::MpfrDigits): when they did not, each raised it for its own n and the
// other's root finding failed ("no reliable root of Q_n").  Both get the lines of window_lower_bound and r_crit,2
// computed alone.  r_min = 0.07182: n = 1..93, all by the MPFR route, none computed by an earlier case.
TEST(WindowOverlays, TwoCallersAtOnceGetTheBoundsComputedAlone) {
  const double r_min = 0.07182, r_max = 0.3;
  std::vector<std::pair<double, int>> got[2];
  std::exception_ptr failed[2];
  std::vector<std::thread> callers;
  for (int k = 0; k < 2; ++k)
    callers.emplace_back([&, k] {
      try {
        got[k] = window_overlay(r_min, r_max, nullptr, 1);
      } catch (...) {
        failed[k] = std::current_exception();
      }
    });
  for (auto& t : callers) t.join();
  for (int k = 0; k < 2; ++k)
    if (failed[k]) {
      try {
        std::rethrow_exception(failed[k]);
      } catch (const std::exception& e) {
        FAIL() << "caller " << k << ": " << e.what();
      }
    }
  std::vector<std::pair<double, int>> want;
  for (int n = 1; n <= window_overlay_last_n(r_min); ++n) {
    const double up = n >= 2 ? static_cast<double>(r_crit2(n, 20)) : 1.0,
                 lo = static_cast<double>(window_lower_bound(n, 20));
    if (n >= 2 && up <= r_max) want.push_back({up, 0});
    if (lo >= r_min && lo <= r_max) want.push_back({lo, 1});
  }
  EXPECT_EQ(window_overlay_last_n(r_min), 93);
  EXPECT_EQ(got[0], want);
  EXPECT_EQ(got[1], want);
}

TEST(WindowOverlays, LinesAreTheBoundsInTheRange) {
  const auto lines = window_overlay(0.09, 0.2);
  // n = 2: lower 0.12754..., r_crit,2 = 3 - 2 sqrt 2; n = 3: lower 0.09452, r_crit,2 = 5 - 2 sqrt 6; n = 1's lower
  // 3 - 2 sqrt 2 too.
  std::vector<std::pair<double, int>> want = {{static_cast<double>(r_crit2(2, 20)), 0},
                                              {static_cast<double>(window_lower_bound(1, 20)), 1},
                                              {static_cast<double>(window_lower_bound(2, 20)), 1},
                                              {static_cast<double>(r_crit2(3, 20)), 0},
                                              {static_cast<double>(window_lower_bound(3, 20)), 1}};
  auto sorted = [](std::vector<std::pair<double, int>> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  EXPECT_EQ(sorted(lines), sorted(want));
  for (const auto& [r, colour] : stripes_overlay(0.2, 0.3)) {
    EXPECT_GE(r, 0.2);
    EXPECT_LE(r, 0.3);
    EXPECT_EQ(colour, 1);
  }
}

}  // namespace
