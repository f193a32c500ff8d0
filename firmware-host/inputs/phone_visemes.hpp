// Phone labels and Rhubarb mouth shapes as MPEG-4 visemes (ISO/IEC 14496-2
// Annex C; indices as in config/fap/visemes.yaml).
#pragma once

#include <string_view>

namespace facectl {

// MPEG-4 viseme indices, named as in config/fap/visemes.yaml.
enum Viseme : int {
  kVisemeNone = 0,
  kVisemePBM = 1,
  kVisemeFV = 2,
  kVisemeTh = 3,
  kVisemeTD = 4,
  kVisemeKG = 5,
  kVisemeChJSh = 6,
  kVisemeSZ = 7,
  kVisemeNL = 8,
  kVisemeR = 9,
  kVisemeA = 10,
  kVisemeE = 11,
  kVisemeI = 12,
  kVisemeO = 13,
  kVisemeU = 14,
};
inline constexpr int kVisemeCount = 15;

// The viseme of one phone label, or -1 for a label not in these tables (the
// caller notes it and uses 0). Tried in this order:
// 1. Silence (ASCII case-insensitive): "" sil sp spn <eps> <sil> pau, and "#"
//    (SPPAS) -> 0.
// 2. ARPAbet (CMU set plus TIMIT's AX AXR IX UX DX NX EL EM EN Q WH), case-
//    insensitive, one trailing stress digit 0/1/2 dropped:
//      P B M EM -> 1 p_b_m   F V -> 2 f_v        TH DH -> 3 th
//      T D DX Q -> 4 t_d     K G NG HH -> 5 k_g  CH JH SH ZH -> 6 ch_j_sh
//      S Z -> 7 s_z          N L NX EL EN -> 8 n_l   R ER AXR -> 9 r
//      AA AE AH AW AY -> 10 a   EH EY AX, and AH0 (schwa) -> 11 e
//      IH IY IX Y -> 12 i       AO OW OY -> 13 o     UH UW UX W WH -> 14 U
//    Diphthongs take the viseme of their first, more open part; HH, with no
//    lip shape of its own, goes with the open k_g; ER is lip-rounded like r.
// 3. IPA as Montreal Forced Aligner's english_mfa model writes it, after
//    dropping length, aspiration, palatalisation, labialisation and stress marks
//    (U+02B0..U+02FF), combining diacritics and tie bars, and ASCII ':':
//      p b m kp ɡb -> 1   f v ɱ -> 2   θ ð -> 3   t d ɾ ʔ -> 4
//      k ɡ g ŋ c ɟ x ɣ q h ɦ -> 5   tʃ dʒ ʧ ʤ ʃ ʒ ç -> 6   s z -> 7
//      n l ɫ ɲ ʎ ɬ -> 8   ɹ r ɻ ɚ ɝ -> 9   ɑ a ɐ ʌ æ aj aɪ aw aʊ -> 10
//      ə ɛ e ɜ ej eɪ -> 11   ɪ i ɨ j -> 12   ɔ o ɒ ow oʊ əʊ ɔj ɔɪ oj -> 13
//      ʊ u ʉ w ɥ -> 14
// 4. A few X-SAMPA symbols SPPAS writes that no ARPAbet phone spells:
//      { A -> 10   @ E -> 11   I -> 12   O -> 13   U -> 14   3 3r -> 9
//      tS dZ -> 6. Its S Z T D N V Q read as ARPAbet here (s z t d n v,
//      glottal stop); viseme_of_sampa_phone reads them as SAMPA.
int viseme_of_phone(std::string_view label);

// As viseme_of_phone, for a tier in SPPAS's X-SAMPA (PhonAlign): its
// capitals first (V S Z T D N Q are ʌ ʃ ʒ θ ð ŋ ɒ there, not ARPAbet's
// v s z t d n and glottal stop), then the table above.
int viseme_of_sampa_phone(std::string_view label);

// Rhubarb Lip Sync's mouth shapes (README "Mouth shapes"):
//   A closed lips (P B M) -> 1 p_b_m
//   B slightly open, clenched teeth (most consonants: K S T, also EE) -> 7 s_z:
//     teeth together with spread lips is the s/z pose; t_d opens the jaw more.
//   C open (EH AE) -> 11 e       D wide open (AA) -> 10 a
//   E slightly rounded (AO ER) -> 13 o   F puckered (UW OW W) -> 14 U
//   G upper teeth on lower lip (F V) -> 2 f_v   H tongue up (L) -> 8 n_l
//   X idle, rest -> 0
// Anything else (lower case, the fork's I..L) -> -1.
int viseme_of_rhubarb_shape(char shape);

}  // namespace facectl
