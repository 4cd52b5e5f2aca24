// expect: 'SetString' sets an option or parameter by a computed name
SetString(StrCat("General.", "OptionsFileName"), "@WATCH@/o");
