// expect: 'General' sets an option that names a file or program (General.OptionsFileName)
General.OptionsFileName = StrCat("@WATCH@", "/o.opt");
