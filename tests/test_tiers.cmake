# The test tiers (docs/building.md "Test tiers"): ctest includes this file after the GoogleTest
# lists that gtest_discover_tests wrote, and labels every discovered test with its layer (the
# folder of tests/ its binary is built from) and `fast` or `slow`. A test is slow when it is named
# below: each took over a second on 2 cores (AMD EPYC, release build), with the reason it cannot
# be quicker at the same power. `ctest -L fast` is the inner loop; CI runs both tiers.
# An entry ending in `*` names every test that starts with it; any other entry one test.
set(glintlab_slow_tests
  # A claim run end to end at its quick sample counts, then its near-truth control: the sample
  # counts are the claim's power (verify/claims/*.cpp).
  "Checks/QuickBudget.*"
  "AcrossClaims.StabilityVerdictAndControl"
  "Properties/ControlRejected.ByTheSameDecision/kneiphof_klein_sampler_covers_value"
  # sampler-covers-value of both Kemppinen models at quick, with the mixture and with Algorithm 2
  # alone (10^5 samples and up to 4 · 10^5 reference evaluations per setting).
  "KemppinenSampler.*"
  # Chi-square and integration checks whose sample sizes set what they can detect.
  "ChiSquareClaims.EtoPdfMatchesControlsRejected"
  "ChiSquareClaims.IdenticalWithOneAndTwoThreads"
  "ChiSquareClaims.SamplerMatchesPdfControlsRejected"
  "LightsChiSquare.PolygonSamplersMatchTheirPdfsAndControlsAreRejected"
  "LightsChiSquare.RectangleSamplersMatchTheirPdfsAndControlsAreRejected"
  "NdfIdentities.ProjectedAreaIsOmegaZAndSmithArea<glintlab::Beckmann<double>>"
  "NdfIdentities.ProjectedAreaIsOmegaZAndSmithArea<glintlab::GGX<double>>"
  "NdfIdentities.VisibleNormalsNormalized<glintlab::Beckmann<double>>"
  "NdfIdentities.VisibleNormalsNormalized<glintlab::GGX<double>>"
  "SamplerNormalization.PdfIntegratesToOneOverTheSphere"
  "AdequacyClosedForms.RealtimeMomentsMatchItsDraws"
  "ChermainClaims.DictionaryConverges"
  "ChermainClaims.GgaaDecisionFailsAgainstNearTruth"
  "ChermainClaims.LeanMarginNegativeAgainstNearTruth"
  "ChermainPatchSdf.NormalizedWithAndWithoutGgaa"
  "ChermainScalarIdentity.ModelMatchesTheHostCode"
  "KneiphofClaims.DiscreteNdfMean"
  "ZirrKaplanyan.CountMeanAndVarianceMatchADirectlySimulatedBinomial"
  # The glintlab executable run end to end on a subcommand's quick budget (a figure, a sweep, a
  # report, compare, adequacy), or a fuzz loop of a fixed number of inputs.
  "AdequacyTest.OutputDoesNotDependOnThreads"
  "AdequacyTest.QuickRunWritesTableAndMaps"
  "ChermainCli.Fig3Quick"
  "ChermainCli.Fig7Quick"
  "ChermainCli.Fig9Quick"
  "CompareTest.PluginModelBesideThePapersModelsAndThreadIndependent"
  "CompareTest.ReadsVerdictsAndFailureRegionsFromEarlierRuns"
  "ExampleModel.AppearsInTheStabilityClaim"
  "ExampleModel.GetsTheRegistryDrivenFigure"
  "FigureTest.EnvironmentMapFromExr"
  "FigureTest.Fig4QuickWritesExrPngAndCsv"
  "FigureTest.RmseSppQuickWritesExrPngAndCsv"
  "FuzzCli.*"
  "FuzzEnvironmentExr.*"
  "KemppinenFig7Test.ConvergenceUnderEnvironmentLight"
  "KemppinenFigureTest.Fig2_3DiskAndHemisphere"
  "KemppinenTimingTest.FiguresReadTheBenchmarkJson"
  "KemppinenTimingTest.SpeedAccuracyWithoutJson"
  "PluginTest.SweepFigureAndGenericClaimCoverThePluginModel"
  "PodeeCliTest.DistanceAndFlickerQuick"
  "ReportTest.ReuseReadsCachedResultsAndAMalformedOneLeavesTheOldReport"
  "ReportTest.SmallRealRun"
  # Every batched kernel or model on every ISA against its scalar instantiation, on enough rows
  # to reach the recorded worst cases (tests/simd/).
  "SimdChermainEquivalence.DoubleEveryIsa"
  "SimdChermainEquivalence.FloatColumnsRunOnDoubleBatches"
  "SimdChermainNegativeControl.UnperturbedBatchPassesPerturbedFail"
  "SimdEquivalence.*"
  "SimdKemppinenEquivalence.*"
  "SimdModelEquivalence.*")

# The test binaries and the layer label of their tests.
set(glintlab_test_binaries
  glintlab_core_tests glintlab_verify_tests glintlab_experiments_tests glintlab_examples_tests
  glintlab_cli_tests glintlab_simd_tests)
set(glintlab_test_layers core verify experiments examples cli simd)

foreach(binary layer IN ZIP_LISTS glintlab_test_binaries glintlab_test_layers)
  foreach(test IN LISTS ${binary}_TESTS)
    set(tier fast)
    foreach(entry IN LISTS glintlab_slow_tests)
      if(entry MATCHES "^(.*)\\*$")
        string(FIND "${test}" "${CMAKE_MATCH_1}" at)
        if(at EQUAL 0)
          set(tier slow)
          break()
        endif()
      elseif(test STREQUAL entry)
        set(tier slow)
        break()
      endif()
    endforeach()
    set_tests_properties("${test}" PROPERTIES LABELS "${layer};${tier}")
  endforeach()
endforeach()
