// expect: 'General' sets General.SaveSession
General.SaveSession = 1;
